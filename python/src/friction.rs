//! Friction on numbers, bound thinly through the law registry and the highest-level entry points
//! of the numerics, so the binding follows the friction laws as they are added: a law is built
//! by name from the registry (`friction::find_law`, parameters at their defaults unless given),
//! then either the statistical static friction coefficient μ_s of a rough surface
//! (`friction::static_friction_curve`) from its summit statistics at nominal pressures, or the
//! per-spot model on a contact solution of two bodies (`friction::per_spot_friction`, the one
//! call the study's node makes too), or the per-summit model on it
//! (`friction::per_summit_friction` over the summits of the composite height, each with
//! `friction::summit_interference`), as a study's friction node applies them.

use std::collections::HashMap;
use std::sync::Arc;

use asperity::friction::{
    find_law, law_names, per_spot_friction as spot_friction,
    per_summit_friction as summits_friction, static_friction_curve, summit_interference,
    AdhesionBeyondFits, AdhesionParameters, BodyHardness, BodyMaps, Connectivity, ContactBodies,
    ContactSection, FrictionLaw, LawInputs, Material, PerSummitResult, SectionFriction,
    SolveSettings, StatisticalModel, SummitContact, SummitFriction, SummitStatistics,
};
use asperity::materials::{BodyConstants, BodyMaterial, MaterialPair};
use asperity::nodes::validity::cross::pressure_within_flow;
use asperity::nodes::{DEFAULT_ADHESION_ENERGY, DEFAULT_EQUILIBRIUM_DISTANCE};
use asperity::surface::{find_summits, Boundary, HeightMap, SummitOptions};
use ndarray::ArrayView2;
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::{compute, value_error};
use crate::laws::{parameter_value, Parameter};
use crate::row::{key, set_coefficient, set_field, spot, summit};
use asperity::nodes::{beyond_fit_field, share};
use asperity::units::Dimension::{Area, Dimensionless, Force, Length, Pressure};
use asperity::vocabulary::metrics::{
    ADHESION_FORCE, CONTACTS, D_STAR, EXTERNAL_LOAD, FRICTION_FORCE, LOAD_SHARE_MERGED,
    LOAD_SHARE_OUTSIDE_REGIME, LOAD_SHARE_WITHOUT_RADIUS, MU_DEFORMATION,
    MU_DEFORMATION_SLOPE_BASELINE, NOMINAL_PRESSURE, NORMAL_LOAD, PLASTICITY_INDEX, PLOUGHING_BODY,
    REAL_AREA, SEPARATION, SPOTS_WITHOUT_RADIUS, SPOT_COUNT, SUMMIT_COUNT,
};
use asperity::vocabulary::{spot_columns as spots, summit_columns as summits};

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(static_friction, m)?)?;
    m.add_function(wrap_pyfunction!(per_spot_friction, m)?)?;
    m.add_function(wrap_pyfunction!(per_summit_friction, m)?)?;
    m.add("DEFAULT_ADHESION_ENERGY", DEFAULT_ADHESION_ENERGY)?;
    m.add("DEFAULT_EQUILIBRIUM_DISTANCE", DEFAULT_EQUILIBRIUM_DISTANCE)?;
    Ok(())
}

/// The law `model` of the registry, built for `material` with the softer body's yield strength
/// Y (Pa; default Tabor's H/2.8) and shear strength k (Pa; default Y/√3) and `parameters`
/// overriding the law's defaults.
fn build_law(
    model: &str,
    material: Material,
    yield_strength: Option<f64>,
    shear_strength: Option<f64>,
    parameters: HashMap<String, Parameter>,
) -> PyResult<Arc<dyn FrictionLaw>> {
    let descriptor = find_law(model).ok_or_else(|| {
        value_error(
            "model",
            format!(
                "'{model}' is not a friction law; expected one of: {}",
                law_names().join(", ")
            ),
        )
    })?;
    let mut values = descriptor.default_parameters();
    for (name, value) in parameters {
        let spec = descriptor.parameter(&name).ok_or_else(|| {
            let known: Vec<_> = descriptor.parameters.iter().map(|p| p.name).collect();
            value_error(
                "parameters",
                format!(
                    "'{model}' has no parameter '{name}'; its parameters: {}",
                    known.join(", ")
                ),
            )
        })?;
        values.set(&name, parameter_value(model, spec, value)?);
    }
    let yield_strength = yield_strength.unwrap_or_else(|| material.tabor_yield_strength());
    let inputs = LawInputs {
        material,
        yield_strength,
        shear_strength: shear_strength.unwrap_or(yield_strength / 3f64.sqrt()),
        parameters: values,
    };
    (descriptor.build)(&inputs)
        .map(Arc::from)
        .map_err(|e| value_error("model", e))
}

/// The pair's friction material from E* (Pa), the softer body's H (Pa) and ν.
fn material(composite_modulus: f64, hardness: f64, poisson_ratio: f64) -> PyResult<Material> {
    Material::new(composite_modulus, hardness, poisson_ratio)
        .map_err(|e| value_error("material", e))
}

/// The adhesion energy Δγ (N/m) and Lennard-Jones distance ε (m).
fn adhesion(energy: f64, equilibrium_distance: f64) -> PyResult<AdhesionParameters> {
    AdhesionParameters::new(energy, equilibrium_distance)
        .map_err(|e| value_error("adhesion_energy", e))
}

/// Summit statistics from `(m0, m2, m4)` (m², 1, 1/m²) or `(σ_s, R, η)` (m, m, 1/m²).
fn summits(
    moments: Option<(f64, f64, f64)>,
    explicit: Option<(f64, f64, f64)>,
) -> PyResult<SummitStatistics> {
    match (moments, explicit) {
        (Some((m0, m2, m4)), None) => {
            SummitStatistics::from_moments(m0, m2, m4).map_err(|e| value_error("moments", e))
        }
        (None, Some((sigma, radius, density))) => {
            SummitStatistics::from_explicit(sigma, radius, density)
                .map_err(|e| value_error("summits", e))
        }
        _ => Err(value_error(
            "moments",
            "give either the spectral moments (m0, m2, m4) or the summits (sigma_s, radius, density)",
        )),
    }
}

/// μ_s and the separation solve at each nominal pressure (Pa); see `asperity.static_friction`.
#[pyfunction]
#[pyo3(signature = (model, composite_modulus, hardness, poisson_ratio, nominal_pressures, nominal_area, moments=None, summits_explicit=None, adhesion_energy=DEFAULT_ADHESION_ENERGY, equilibrium_distance=DEFAULT_EQUILIBRIUM_DISTANCE, parameters=HashMap::new(), yield_strength=None, shear_strength=None))]
#[allow(clippy::too_many_arguments)]
fn static_friction<'py>(
    py: Python<'py>,
    model: &str,
    composite_modulus: f64,
    hardness: f64,
    poisson_ratio: f64,
    nominal_pressures: Vec<f64>,
    nominal_area: f64,
    moments: Option<(f64, f64, f64)>,
    summits_explicit: Option<(f64, f64, f64)>,
    adhesion_energy: f64,
    equilibrium_distance: f64,
    parameters: HashMap<String, Parameter>,
    yield_strength: Option<f64>,
    shear_strength: Option<f64>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let summits = summits(moments, summits_explicit)?;
    let material = material(composite_modulus, hardness, poisson_ratio)?;
    for (i, &p) in nominal_pressures.iter().enumerate() {
        pressure_within_flow(p, hardness)
            .map_err(|e| value_error(&format!("nominal_pressures[{i}]"), e))?;
    }
    let law = build_law(model, material, yield_strength, shear_strength, parameters)?;
    let laws = law.asperity_laws().ok_or_else(|| {
        value_error("model", format!("'{model}' has no single-asperity laws for the statistical method; use per_spot_friction"))
    })?;
    let adhesion = adhesion(adhesion_energy, equilibrium_distance)?;
    let forces: Vec<f64> = nominal_pressures.iter().map(|p| p * nominal_area).collect();
    let results = compute(py, || {
        let model = StatisticalModel::new(
            laws,
            summits,
            material,
            adhesion,
            nominal_area,
            AdhesionBeyondFits::default(),
        )
        .map_err(|e| value_error("nominal_area", e))?;
        static_friction_curve(&model, &forces, &SolveSettings::default())
            .map_err(|e| value_error("model", e))
    })?;
    results
        .into_iter()
        .zip(&nominal_pressures)
        .map(|(r, p)| {
            let r = r.map_err(|e| value_error("nominal_pressures", format!("at {p:e} Pa: {e}")))?;
            let d = PyDict::new(py);
            d.set_item(key(NOMINAL_PRESSURE, Pressure), p)?;
            set_coefficient(&d, r.mu_s)?;
            d.set_item(key(FRICTION_FORCE, Force), r.static_friction_force)?;
            d.set_item(key(EXTERNAL_LOAD, Force), r.external_load)?;
            d.set_item(key(NORMAL_LOAD, Force), r.contact_load)?;
            d.set_item(key(ADHESION_FORCE, Force), r.adhesion_force)?;
            d.set_item(key(REAL_AREA, Area), r.real_contact_area)?;
            d.set_item(D_STAR, r.d_star)?;
            d.set_item(key(SEPARATION, Length), r.separation_from_heights)?;
            d.set_item(PLASTICITY_INDEX, r.plasticity_index)?;
            d.set_item(CONTACTS, r.contacting_summits)?;
            set_field(&d, beyond_fit_field(r.load_beyond_fit, r.contact_load))?;
            Ok(d)
        })
        .collect()
}

/// A body of the per-spot binding from (E (Pa), ν, H (Pa)).
fn body(
    name: &str,
    (youngs_modulus, poisson_ratio, hardness): (f64, f64, f64),
) -> PyResult<BodyMaterial> {
    BodyMaterial::new(BodyConstants::with_hardness(
        youngs_modulus,
        poisson_ratio,
        hardness,
    ))
    .map_err(|e| value_error(name, e))
}

/// The maps of a contact solution the per-spot binding reads, as given.
struct SpotMaps<'py> {
    pressure: PyReadonlyArray2<'py, f64>,
    gap: PyReadonlyArray2<'py, f64>,
    composite_height: PyReadonlyArray2<'py, f64>,
    upper_height: Option<PyReadonlyArray2<'py, f64>>,
    deformation_lower: PyReadonlyArray2<'py, f64>,
    deformation_upper: Option<PyReadonlyArray2<'py, f64>>,
    plastic_penetration: PyReadonlyArray2<'py, f64>,
}

impl SpotMaps<'_> {
    fn bodies(&self, pair: &MaterialPair) -> PyResult<ContactBodies<'_>> {
        let maps = BodyMaps {
            composite_height: self.composite_height.as_array(),
            upper_height: self.upper_height.as_ref().map(|z| z.as_array()),
            deformation_lower: self.deformation_lower.as_array().into(),
            deformation_upper: self.deformation_upper.as_ref().map(|u| u.as_array().into()),
            plastic_penetration: self.plastic_penetration.as_array().into(),
        };
        ContactBodies::new(maps, BodyHardness::of(pair)).map_err(|e| value_error("result", e))
    }
}

/// μ_s of a contact solution, spot by spot, by the numerics' one per-spot call (the study's
/// node makes the same); see `asperity.per_spot_friction`.
#[pyfunction]
#[pyo3(signature = (pressure, gap, composite_height, deformation_lower, plastic_penetration, dx, dy, model, lower_body, upper_body=None, upper_height=None, deformation_upper=None, periodic=true, eight_connected=false, adhesion_energy=DEFAULT_ADHESION_ENERGY, equilibrium_distance=DEFAULT_EQUILIBRIUM_DISTANCE, parameters=HashMap::new(), yield_strength=None, shear_strength=None))]
#[allow(clippy::too_many_arguments)]
fn per_spot_friction<'py>(
    py: Python<'py>,
    pressure: PyReadonlyArray2<'py, f64>,
    gap: PyReadonlyArray2<'py, f64>,
    composite_height: PyReadonlyArray2<'py, f64>,
    deformation_lower: PyReadonlyArray2<'py, f64>,
    plastic_penetration: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    model: &str,
    lower_body: (f64, f64, f64),
    upper_body: Option<(f64, f64, f64)>,
    upper_height: Option<PyReadonlyArray2<'py, f64>>,
    deformation_upper: Option<PyReadonlyArray2<'py, f64>>,
    periodic: bool,
    eight_connected: bool,
    adhesion_energy: f64,
    equilibrium_distance: f64,
    parameters: HashMap<String, Parameter>,
    yield_strength: Option<f64>,
    shear_strength: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let upper = upper_body.map(|b| body("upper_material", b)).transpose()?;
    let pair = MaterialPair::new(body("material", lower_body)?, upper);
    let material = Material::from_pair(&pair).map_err(|e| value_error("material", e))?;
    let (_, softer) = pair.softer();
    let yield_strength = yield_strength.or(softer.yield_strength());
    let shear_strength = shear_strength.or(softer.shear_strength());
    let law = build_law(model, material, yield_strength, shear_strength, parameters)?;
    let maps = SpotMaps {
        pressure,
        gap,
        composite_height,
        upper_height,
        deformation_lower,
        deformation_upper,
        plastic_penetration,
    };
    let section = ContactSection {
        pressure: maps.pressure.as_array(),
        gap: maps.gap.as_array().into(),
        bodies: maps.bodies(&pair)?,
        spacing: (dx, dy),
        periodic,
        connectivity: if eight_connected {
            Connectivity::Eight
        } else {
            Connectivity::Four
        },
        adhesion: adhesion(adhesion_energy, equilibrium_distance)?,
    };
    let found = compute(py, || {
        spot_friction(&section, law.as_ref()).map_err(|e| value_error("result", e))
    })?;
    spot_dict(py, &found)
}

/// The per-spot result as Python reads it (see `asperity.per_spot_friction`).
fn spot_dict<'py>(py: Python<'py>, found: &SectionFriction) -> PyResult<Bound<'py, PyDict>> {
    let (spots, result) = (&found.spots, &found.result);
    let d = PyDict::new(py);
    let net = result.total_normal_force - result.adhesion_force;
    set_coefficient(&d, result.mu_s)?;
    d.set_item(
        MU_DEFORMATION,
        result.mu_s.map(|_| result.total_deformation_force / net),
    )?;
    let load = result.total_normal_force;
    d.set_item(key(NORMAL_LOAD, Force), load)?;
    d.set_item(key(FRICTION_FORCE, Force), result.total_friction_force)?;
    d.set_item(
        key(spots::DEFORMATION_FORCE, Force),
        result.total_deformation_force,
    )?;
    d.set_item(key(REAL_AREA, Area), result.total_area)?;
    d.set_item(key(ADHESION_FORCE, Force), result.adhesion_force)?;
    set_field(&d, beyond_fit_field(result.load_beyond_fit, load))?;
    d.set_item(
        LOAD_SHARE_WITHOUT_RADIUS,
        share(result.load_without_radius, load),
    )?;
    d.set_item(LOAD_SHARE_MERGED, share(result.load_merged, load))?;
    d.set_item(
        LOAD_SHARE_OUTSIDE_REGIME,
        share(result.load_outside_regime, load),
    )?;
    d.set_item(SPOT_COUNT, spots.len())?;
    d.set_item(SPOTS_WITHOUT_RADIUS, result.spots_without_radius)?;
    if let Some(geometry) = &found.geometry {
        d.set_item(PLOUGHING_BODY, geometry.ploughing.name())?;
        d.set_item(MU_DEFORMATION_SLOPE_BASELINE, geometry.slope_baseline)?;
    }
    let column = |f: &dyn Fn(usize) -> f64| (0..spots.len()).map(f).collect::<Vec<f64>>();
    d.set_item(spot(spots::NORMAL_FORCE, Force), column(&|i| spots[i].load))?;
    d.set_item(spot(spots::AREA, Area), column(&|i| spots[i].area))?;
    d.set_item(
        spot(spots::RADIUS, Length),
        spots.iter().map(|s| s.radius).collect::<Vec<_>>(),
    )?;
    d.set_item(
        spot(spots::SUMMITS, Dimensionless),
        spots.iter().map(|s| s.summits).collect::<Vec<_>>(),
    )?;
    d.set_item(
        spot(spots::FRICTION_FORCE, Force),
        column(&|i| result.spots[i].friction_force),
    )?;
    d.set_item(
        spot(spots::DEFORMATION_FORCE, Force),
        column(&|i| result.spots[i].deformation_force),
    )?;
    Ok(d)
}

/// μ_s of a contact solution, summit by summit; see `asperity.per_summit_friction`.
#[pyfunction]
#[pyo3(signature = (composite_height, pressure, gap, deformation, plastic_penetration, dx, dy, model, composite_modulus, hardness, poisson_ratio, periodic=true, adhesion_energy=DEFAULT_ADHESION_ENERGY, equilibrium_distance=DEFAULT_EQUILIBRIUM_DISTANCE, parameters=HashMap::new(), yield_strength=None))]
#[allow(clippy::too_many_arguments)]
fn per_summit_friction<'py>(
    py: Python<'py>,
    composite_height: PyReadonlyArray2<'py, f64>,
    pressure: PyReadonlyArray2<'py, f64>,
    gap: PyReadonlyArray2<'py, f64>,
    deformation: PyReadonlyArray2<'py, f64>,
    plastic_penetration: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    model: &str,
    composite_modulus: f64,
    hardness: f64,
    poisson_ratio: f64,
    periodic: bool,
    adhesion_energy: f64,
    equilibrium_distance: f64,
    parameters: HashMap<String, Parameter>,
    yield_strength: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let material = material(composite_modulus, hardness, poisson_ratio)?;
    let law = build_law(model, material, yield_strength, None, parameters)?;
    let laws = Arc::clone(&law).asperity_laws().ok_or_else(|| {
        value_error(
            "model",
            format!("'{model}' has no single-asperity laws: use per_spot_friction"),
        )
    })?;
    let adhesion = adhesion(adhesion_energy, equilibrium_distance)?;
    let z = composite_height.as_array().to_owned();
    let [p, g, u, u_pl] = same_shape(
        z.dim(),
        [
            ("pressure", pressure.as_array()),
            ("gap", gap.as_array()),
            ("deformation", deformation.as_array()),
            ("plastic_penetration", plastic_penetration.as_array()),
        ],
    )?;
    let (contacts, result) = compute(py, || {
        let map = HeightMap::new(z, dx, dy).map_err(|e| value_error("composite_height", e))?;
        let boundary = if periodic {
            Boundary::Periodic
        } else {
            Boundary::Open
        };
        let options = SummitOptions {
            boundary,
            min_height: None,
            min_prominence: None,
        };
        let found = find_summits(&map, options).map_err(|e| value_error("composite_height", e))?;
        let contacts: Vec<SummitContact> = found
            .summits
            .iter()
            .filter(|s| s.radius.is_finite() && s.radius > 0.0)
            .map(|s| {
                let at = |a: &ArrayView2<f64>| a[(s.iy, s.ix)];
                SummitContact {
                    radius: s.radius,
                    interference: summit_interference(at(&p), at(&u), at(&u_pl), at(&g)),
                }
            })
            .collect();
        let result = summits_friction(
            &contacts,
            laws.as_ref(),
            &material,
            &adhesion,
            AdhesionBeyondFits::default(),
        )
        .map_err(|e| value_error("model", e))?;
        Ok((contacts, result))
    })?;
    summit_dict(py, &contacts, &result)
}

/// The contact solution's fields, each checked to have the composite height's shape `dim`.
fn same_shape<'a, const N: usize>(
    dim: (usize, usize),
    fields: [(&str, ArrayView2<'a, f64>); N],
) -> PyResult<[ArrayView2<'a, f64>; N]> {
    for (name, a) in &fields {
        if a.dim() != dim {
            return Err(value_error(
                name,
                format!("has shape {:?}; composite_height has {dim:?}", a.dim()),
            ));
        }
    }
    Ok(fields.map(|(_, a)| a))
}

/// The per-summit result: μ_s, the totals (N) and one list per summit column.
fn summit_dict<'py>(
    py: Python<'py>,
    contacts: &[SummitContact],
    result: &PerSummitResult,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    set_coefficient(&d, result.mu_s)?;
    d.set_item(key(NORMAL_LOAD, Force), result.total_normal_force)?;
    d.set_item(key(ADHESION_FORCE, Force), result.total_adhesion_force)?;
    d.set_item(key(FRICTION_FORCE, Force), result.total_friction_force)?;
    set_field(
        &d,
        beyond_fit_field(result.load_beyond_fit, result.total_normal_force),
    )?;
    d.set_item(SUMMIT_COUNT, contacts.len())?;
    let column = |f: fn(&SummitFriction) -> f64| result.summits.iter().map(f).collect::<Vec<_>>();
    d.set_item(
        summit(summits::RADIUS, Length),
        contacts.iter().map(|c| c.radius).collect::<Vec<_>>(),
    )?;
    d.set_item(
        summit(summits::INTERFERENCE, Length),
        contacts.iter().map(|c| c.interference).collect::<Vec<_>>(),
    )?;
    d.set_item(
        summit(summits::NORMAL_FORCE, Force),
        column(|s| s.normal_force),
    )?;
    d.set_item(
        summit(summits::FRICTION_FORCE, Force),
        column(|s| s.friction_force),
    )?;
    d.set_item(
        summit(summits::ADHESION_FORCE, Force),
        column(|s| s.adhesion_force),
    )?;
    Ok(d)
}
