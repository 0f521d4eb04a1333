//! Built-in materials: named elastic and plastic constants with their literature sources.
//!
//! Pure data and a name lookup (no YAML, no engine): studies use the names through
//! `nodes::material_spec`, and may override any value.
//!
//! Every entry gives Young's modulus E, Poisson's ratio ν and a hardness H; the plastic flow
//! pressure p_lim of the elastic–perfectly-plastic contact model follows from H. Conventions:
//!
//! * **Hardness** is the Vickers hardness expressed as a pressure, H = HV · 9.80665 MPa (HV in
//!   kgf/mm²). Where a source gives Rockwell C or Brinell values they are converted to HV with
//!   the ASTM E140 tables (the conversion is stated per entry). H is the "H" of the Kogut–Etsion
//!   models (hardness of the softer body).
//! * **Flow pressure rule: p_lim = H.** The mean pressure under a fully plastic indenter is the
//!   hardness (Tabor, *The Hardness of Metals*, 1951: H ≈ 2.8 σ_y), and the elastic–perfectly-
//!   plastic half-space model caps the local pressure at that value; the reference workflow also
//!   takes p_lim from (ultra-micro-)hardness measurements. Every entry below follows this rule
//!   (the default of [`BodyMaterial`](super::BodyMaterial)); a study can override p_lim separately.
//! * Values are bulk handbook values unless stated; surface layers (grinding, work hardening,
//!   indentation size effect at small depths) can differ substantially, so measured
//!   near-surface values should override them where available.

use super::body::BodyConstants;

/// One built-in material (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuiltinMaterial {
    /// Canonical name, lower case (`s235jr`).
    pub name: &'static str,
    /// Other accepted names, lower case (`1.0037`).
    pub aliases: &'static [&'static str],
    /// One-line description (grade, condition).
    pub description: &'static str,
    /// E, ν and the hardness H (Vickers hardness as a pressure); p_lim = H and the other
    /// strengths by the default rules of [`BodyMaterial`](super::BodyMaterial).
    pub constants: BodyConstants,
    /// Literature source of the values and the assumptions made.
    pub source: &'static str,
}

/// Vickers hardness number (kgf/mm²) to pascals.
const HV: f64 = 9.806_65e6;

/// The built-in materials.
///
/// * `s235jr` (EN 10025-2 S235JR, 1.0037): E = 210 GPa, ν = 0.3 (EN 1993-1-1:2005 §3.2.6). Bulk
///   hardness ≈ 130 HV from the tensile strength 360–510 MPa (EN 10025-2; HV ≈ R_m/3.3 at mid
///   range). **Near-surface assumption: H = 200 HV (1.96 GPa)**, about 1.5 × bulk, for ground
///   specimens: grinding work-hardens a thin surface layer and ultra-micro-hardness at sub-micron
///   depths shows an indentation size effect; both raise the value the summits see. No measured
///   value was available: override with the ultra-micro-hardness of the actual specimens.
/// * `aisi52100` (100Cr6, 1.3505), through-hardened bearing steel at 61 HRC ≈ 720 HV (ASTM E140):
///   E = 210 GPa, ν = 0.3 (ASM Handbook Vol. 1, 1990; bearing-steel data of 58–65 HRC).
/// * `17-4ph` (1.4542, AISI 630) in condition H900: 44 HRC ≈ 434 HV (ASTM E140), E = 196 GPa,
///   ν = 0.272 (AK Steel 17-4 PH product data bulletin). The material of the static-friction
///   experiments compared with the KE statistical model in the reference workflow.
/// * `al6061-t6`: E = 68.9 GPa, ν = 0.33, 95 HB ≈ 107 HV (ASM Handbook Vol. 2, 1990).
/// * `ti6al4v` (grade 5, annealed): E = 113.8 GPa, ν = 0.342, 349 HV (ASM Materials Properties
///   Handbook: Titanium Alloys, 1994).
pub const BUILTIN_MATERIALS: &[BuiltinMaterial] = &[
    BuiltinMaterial {
        name: "s235jr",
        aliases: &["1.0037", "s235"],
        description: "structural steel S235JR (EN 10025-2), ground specimens",
        constants: BodyConstants::with_hardness(210.0e9, 0.30, 200.0 * HV),
        source: "E, nu: EN 1993-1-1:2005 3.2.6; bulk ~130 HV from Rm 360-510 MPa (EN 10025-2); \
                 near-surface H = 200 HV assumed (~1.5 x bulk: grinding work hardening and \
                 indentation size effect of ultra-micro-hardness); p_lim = H",
    },
    BuiltinMaterial {
        name: "aisi52100",
        aliases: &["52100", "100cr6", "1.3505"],
        description: "bearing steel AISI 52100 / 100Cr6, through-hardened 61 HRC",
        constants: BodyConstants::with_hardness(210.0e9, 0.30, 720.0 * HV),
        source: "ASM Handbook Vol. 1 (1990): E = 210 GPa, nu = 0.3, 58-65 HRC; 61 HRC = 720 HV \
                 (ASTM E140); p_lim = H",
    },
    BuiltinMaterial {
        name: "17-4ph",
        aliases: &["174ph", "1.4542", "aisi630"],
        description: "precipitation-hardening stainless steel 17-4PH, condition H900",
        constants: BodyConstants::with_hardness(196.0e9, 0.272, 434.0 * HV),
        source: "AK Steel 17-4 PH product data bulletin: E = 196 GPa (28.5e6 psi), nu = 0.272, \
                 H900 44 HRC = 434 HV (ASTM E140); p_lim = H",
    },
    BuiltinMaterial {
        name: "al6061-t6",
        aliases: &["6061-t6", "6061", "aa6061-t6"],
        description: "aluminium alloy 6061-T6",
        constants: BodyConstants::with_hardness(68.9e9, 0.33, 107.0 * HV),
        source: "ASM Handbook Vol. 2 (1990): E = 68.9 GPa, nu = 0.33, 95 HB = 107 HV; p_lim = H",
    },
    BuiltinMaterial {
        name: "ti6al4v",
        aliases: &["ti-6al-4v", "grade5", "3.7165"],
        description: "titanium alloy Ti-6Al-4V (grade 5), annealed",
        constants: BodyConstants::with_hardness(113.8e9, 0.342, 349.0 * HV),
        source: "ASM Materials Properties Handbook: Titanium Alloys (1994): E = 113.8 GPa, \
                 nu = 0.342, 349 HV; p_lim = H",
    },
];

/// A material name that is neither a built-in name nor an alias.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("unknown material '{name}'; built-in materials: {}", known_names().join(", "))]
pub struct UnknownMaterial {
    /// The name as given.
    pub name: String,
}

/// Canonical names of the built-in materials.
pub fn known_names() -> Vec<&'static str> {
    BUILTIN_MATERIALS.iter().map(|m| m.name).collect()
}

/// Every accepted name (canonical names and aliases), for suggestions.
pub fn all_names() -> impl Iterator<Item = &'static str> {
    BUILTIN_MATERIALS
        .iter()
        .flat_map(|m| std::iter::once(m.name).chain(m.aliases.iter().copied()))
}

/// Looks a material up by name or alias, ignoring case and surrounding white space.
pub fn find_material(name: &str) -> Result<&'static BuiltinMaterial, UnknownMaterial> {
    let wanted = name.trim().to_lowercase();
    BUILTIN_MATERIALS
        .iter()
        .find(|m| m.name == wanted || m.aliases.contains(&wanted.as_str()))
        .ok_or_else(|| UnknownMaterial {
            name: name.to_string(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookup_ignores_case_and_accepts_aliases() {
        let a = find_material("S235JR").map(|m| m.name);
        let b = find_material(" 1.0037 ").map(|m| m.name);
        assert_eq!(a, Ok("s235jr"));
        assert_eq!(b, Ok("s235jr"));
        assert_eq!(find_material("100Cr6").map(|m| m.name), Ok("aisi52100"));
        assert!(find_material("s253jr").is_err());
    }

    #[test]
    fn names_are_unique_lower_case_and_values_physical() {
        let names: Vec<&str> = all_names().collect();
        for (i, n) in names.iter().enumerate() {
            assert_eq!(*n, n.to_lowercase());
            assert!(!names[i + 1..].contains(n), "duplicate name {n}");
        }
        for m in BUILTIN_MATERIALS {
            let body = super::super::BodyMaterial::new(m.constants);
            assert!(body.is_ok(), "{}: {body:?}", m.name);
            assert!(m.constants.hardness.is_some(), "{}", m.name);
            assert_eq!(
                m.constants.flow_pressure, None,
                "{}: rule p_lim = H",
                m.name
            );
        }
    }
}
