//! Length-unit names as vendors write them, converted to metres.

/// Metres per unit for a length-unit name (`"µm"`, `"um"`, `"Micrometer"`, `"nm"`, `"Å"`, …).
///
/// Case matters only to tell `m` (metre) apart from `M`-prefixed spellings; both the micro
/// sign U+00B5 and the Greek mu U+03BC are accepted. Returns `None` for an unknown name.
pub(crate) fn length_unit_to_metres(unit: &str) -> Option<f64> {
    let u = unit
        .trim()
        .trim_matches(|c| c == '[' || c == ']' || c == '(' || c == ')');
    let lower = u.to_lowercase();
    let factor = match lower.as_str() {
        "m" | "meter" | "meters" | "metre" | "metres" => 1.0,
        "cm" | "centimeter" | "centimeters" | "centimetre" => 1e-2,
        "mm" | "millimeter" | "millimeters" | "millimetre" | "millimetres" => 1e-3,
        "µm" | "μm" | "um" | "micrometer" | "micrometers" | "micrometre" | "micrometres"
        | "micron" | "microns" => 1e-6,
        "nm" | "nanometer" | "nanometers" | "nanometre" | "nanometres" => 1e-9,
        "pm" | "picometer" | "picometers" | "picometre" => 1e-12,
        "å" | "angstrom" | "angstroms" | "ångström" => 1e-10,
        _ => return None,
    };
    Some(factor)
}

#[cfg(test)]
mod tests {
    use super::length_unit_to_metres;

    #[test]
    fn knows_vendor_spellings() {
        assert_eq!(length_unit_to_metres("µm"), Some(1e-6));
        assert_eq!(length_unit_to_metres("\u{3bc}m"), Some(1e-6));
        assert_eq!(length_unit_to_metres("Micrometer"), Some(1e-6));
        assert_eq!(length_unit_to_metres(" mm "), Some(1e-3));
        assert_eq!(length_unit_to_metres("nm"), Some(1e-9));
        assert_eq!(length_unit_to_metres("m"), Some(1.0));
        assert_eq!(length_unit_to_metres("rad"), None);
    }
}
