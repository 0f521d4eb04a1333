//! The separation solve and μ_s: limits, errors, curves and magnitudes (statistical models).

use asperity_numerics::friction::{
    net_load, static_friction, static_friction_at_pressure, static_friction_curve,
    static_friction_on_grid, AdhesionBeyondFits, AdhesionParameters, FrictionError, Material,
    NetLoadGrid, SolveSettings, StatisticalModel, SummitStatistics,
};

use super::law_support::{laws, statistical, Model, Options};

/// Steel-like model (σ = 1 µm, β = 0.04, E = 115 GPa, H = 2 GPa, ν = 0.3, A_n = 1 cm²) with a
/// prescribed plasticity index ψ and adhesion energy Δγ (N/m).
fn model(psi: f64, energy: f64, kind: Model) -> StatisticalModel {
    let material = Material::new(115e9, 2e9, 0.3).unwrap_or_else(|e| panic!("{e}"));
    let sigma = 1e-6;
    let beta: f64 = 0.04;
    let sigma_s = sigma * (1.0 - 0.8968 / (768.0 * std::f64::consts::PI * beta * beta)).sqrt();
    let c = 2.0 * material.composite_modulus
        / (std::f64::consts::PI * material.hardness_factor() * material.hardness);
    let radius = sigma_s * c * c / (psi * psi);
    let summits = SummitStatistics::from_explicit(sigma, radius, beta / (radius * sigma))
        .unwrap_or_else(|e| panic!("{e}"));
    let adhesion = AdhesionParameters::new(energy, 0.158e-9).unwrap_or_else(|e| panic!("{e}"));
    statistical(kind, summits, material, adhesion, 1e-4, Options::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

fn an_h(m: &StatisticalModel) -> f64 {
    m.nominal_area * m.material.hardness
}

/// The solution satisfies F = P − F_s: the Brent tolerance 1e-11 in d* and the 1e-10 quadrature
/// keep the residual well below 1e-8.
#[test]
fn solution_balances_the_load() {
    let m = model(1.0, 0.5, Model::KogutEtsion);
    let load = 1e-4 * an_h(&m);
    let r = static_friction(&m, load, &SolveSettings::default()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.status.relative_residual < 1e-8);
    assert!(((r.contact_load - r.adhesion_force) / load - 1.0).abs() < 1e-8);
    assert_eq!(r.status.roots_found, 1);
    assert!(r.status.brent_iterations > 0);
    assert!(r.status.max_integral_relative_error <= 1e-10);
    let mu = r.mu_s.unwrap_or(f64::NAN);
    assert!((mu - r.static_friction_force / load).abs() <= 1e-15 * mu);
    assert!((r.separation_from_heights - r.separation_from_summits - m.summits.y_s).abs() < 1e-18);
    assert!(r.contacting_summits > 0.0 && r.real_contact_area > 0.0);
    // The same load given as a nominal pressure (F / A_n) gives the same solution (rounding).
    let by_pressure =
        static_friction_at_pressure(&m, load / m.nominal_area, &SolveSettings::default())
            .unwrap_or_else(|e| panic!("{e}"));
    assert!((by_pressure.d_star - r.d_star).abs() < 1e-9);
}

/// Δγ = 0 removes adhesion exactly; F_s is linear in Δγ (1e-12, rounding only) and μ_s(Δγ → 0)
/// tends to the non-adhesive value (Δγ = 1e-6 N/m changes μ by < 1e-5 relative).
#[test]
fn zero_adhesion_energy_removes_adhesion() {
    let settings = SolveSettings::default();
    let m0 = model(1.0, 0.0, Model::KogutEtsion);
    let load = 1e-4 * an_h(&m0);
    let r0 = static_friction(&m0, load, &settings).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r0.adhesion_force, 0.0);
    assert!(((r0.contact_load) / load - 1.0).abs() < 1e-8);
    let f1 = model(1.0, 0.25, Model::KogutEtsion)
        .adhesion_force(1.0)
        .unwrap_or_else(|e| panic!("{e}"));
    let f2 = model(1.0, 0.5, Model::KogutEtsion)
        .adhesion_force(1.0)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((f2.total() / f1.total() - 2.0).abs() < 1e-12);
    let small = static_friction(&model(1.0, 1e-6, Model::KogutEtsion), load, &settings)
        .unwrap_or_else(|e| panic!("{e}"));
    let (mu0, mu_small) = (r0.mu_s.unwrap_or(f64::NAN), small.mu_s.unwrap_or(f64::NAN));
    assert!((mu_small / mu0 - 1.0).abs() < 1e-5);
    assert!(mu_small != mu0);
}

/// At very high ψ (ω_c = σ_s/ψ² tiny) nearly all contacting summits are past x = 110, so the
/// KE model approaches the fully plastic branch: mean real pressure P/A → H (3/K·x·P_c over
/// 2x·A_c = H). Within 2 %: the summits with x ≤ 110 lie in a band of 110/ψ² σ_s = 0.7 % of σ_s.
#[test]
fn very_high_plasticity_index_reaches_fully_plastic_branch() {
    let m = model(120.0, 0.0, Model::KogutEtsion);
    let r = static_friction(&m, 1e-3 * an_h(&m), &SolveSettings::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mean_pressure = r.contact_load / r.real_contact_area;
    assert!(
        (mean_pressure / m.material.hardness - 1.0).abs() < 0.02,
        "{mean_pressure:e}"
    );
    // Low ψ is far from it: mostly elastic, mean pressure well below H.
    let low = model(0.5, 0.0, Model::KogutEtsion);
    let rl = static_friction(&low, 1e-3 * an_h(&low), &SolveSettings::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(rl.contact_load / rl.real_contact_area < 0.5 * low.material.hardness);
}

/// A tensile load below the pull-off load is a typed error; a tensile load between pull-off and 0
/// solves (μ_s is None) with two roots on the grid (the stable one, smallest d*, is taken).
#[test]
fn load_below_pull_off_is_a_typed_error() {
    let m = model(0.5, 1.0, Model::KogutEtsion);
    let settings = SolveSettings::default();
    let mut grid = NetLoadGrid::new(&m, &settings).unwrap_or_else(|e| panic!("{e}"));
    let pull_off = grid.pull_off_load(&m).unwrap_or_else(|e| panic!("{e}"));
    assert!(pull_off < 0.0);
    match static_friction(&m, 2.0 * pull_off, &settings) {
        Err(FrictionError::LoadBelowPullOff {
            load,
            pull_off: reported,
        }) => {
            assert_eq!(load, 2.0 * pull_off);
            assert!((reported / pull_off - 1.0).abs() < 1e-6);
        }
        other => panic!("expected LoadBelowPullOff, got {other:?}"),
    }
    let tensile = static_friction(&m, 0.5 * pull_off, &settings).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(tensile.mu_s, None);
    assert_eq!(tensile.status.roots_found, 2);
    assert!(tensile.status.relative_residual < 1e-8);
    // The pull-off load is the minimum of P − F_s: nearby separations carry more.
    let g = |d: f64| net_load(&m, d).unwrap_or_else(|e| panic!("{e}"));
    assert!(g(tensile.d_star) > pull_off);
}

#[test]
fn invalid_and_out_of_range_loads_are_typed_errors() {
    let m = model(1.0, 0.5, Model::KogutEtsion);
    let settings = SolveSettings::default();
    assert!(matches!(
        static_friction(&m, 0.0, &settings),
        Err(FrictionError::InvalidParameter {
            name: "external_load",
            ..
        })
    ));
    assert!(matches!(
        static_friction(&m, f64::NAN, &settings),
        Err(FrictionError::InvalidParameter { .. })
    ));
    let narrow = SolveSettings {
        d_star_floor: -3.0,
        ..settings
    };
    assert!(matches!(
        static_friction(&m, 0.5 * an_h(&m), &narrow),
        Err(FrictionError::LoadAboveSearchRange { .. })
    ));
}

/// Steel-like inputs give μ_s in the range KE 2004 report (≈ 0.1 to above 1 for ψ ≤ 2 and
/// F/(A_n H) = 1e-5 … 1e-3), decreasing with load and with ψ, and CEB gives less than KE.
#[test]
fn steel_like_magnitudes_and_trends() {
    let settings = SolveSettings::default();
    let mut previous_psi_mu = f64::INFINITY;
    for &psi in &[0.5, 1.0, 2.0] {
        let m = model(psi, 0.5, Model::KogutEtsion);
        let loads: Vec<f64> = [1e-5, 1e-4, 1e-3].iter().map(|f| f * an_h(&m)).collect();
        let curve = static_friction_curve(&m, &loads, &settings).unwrap_or_else(|e| panic!("{e}"));
        let mus: Vec<f64> = curve
            .iter()
            .map(|r| {
                r.as_ref()
                    .map(|r| r.mu_s.unwrap_or(f64::NAN))
                    .unwrap_or(f64::NAN)
            })
            .collect();
        for &mu in &mus {
            assert!((0.1..2.5).contains(&mu), "psi {psi}: mu {mu}");
        }
        assert!(mus.windows(2).all(|w| w[1] < w[0]), "psi {psi}: {mus:?}");
        assert!(mus[1] < previous_psi_mu);
        previous_psi_mu = mus[1];
        let ceb = static_friction(
            &model(psi, 0.5, Model::ChangEtsionBogy),
            loads[1],
            &settings,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(ceb.mu_s.unwrap_or(f64::NAN) <= mus[1] * (1.0 + 1e-9));
    }
}

/// A curve shares one grid; every point equals an independent single solve (1e-9 relative: both
/// converge d* to 1e-11 and integrals to 1e-10).
#[test]
fn curve_matches_independent_solves() {
    let m = model(1.5, 0.5, Model::KogutEtsion);
    let settings = SolveSettings::default();
    // The repeated load is solved on a table already refined around its root: still one root.
    let loads: Vec<f64> = [3e-5, 2e-4, 5e-3, 2e-2, 2e-4]
        .iter()
        .map(|f| f * an_h(&m))
        .collect();
    let curve = static_friction_curve(&m, &loads, &settings).unwrap_or_else(|e| panic!("{e}"));
    for (load, point) in loads.iter().zip(curve) {
        let c = point.unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(c.status.roots_found, 1);
        let s = static_friction(&m, *load, &settings).unwrap_or_else(|e| panic!("{e}"));
        let (a, b) = (c.mu_s.unwrap_or(f64::NAN), s.mu_s.unwrap_or(f64::NAN));
        assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
    }
}

/// Hand-built inconsistent inputs and bad settings are typed errors, not NaN.
#[test]
fn inconsistent_inputs_and_settings_are_rejected() {
    let m = model(1.0, 0.5, Model::KogutEtsion);
    let mut summits = m.summits;
    summits.sigma_s = 2.0 * summits.sigma;
    assert!(matches!(
        StatisticalModel::new(
            m.laws.clone(),
            summits,
            m.material,
            m.adhesion,
            1e-4,
            AdhesionBeyondFits::default()
        ),
        Err(FrictionError::InvalidParameter {
            name: "summit statistics",
            ..
        })
    ));
    let mut material = m.material;
    material.poisson_ratio = f64::NAN;
    assert!(laws(
        Model::KogutEtsion,
        &material,
        asperity_numerics::friction::StaticFrictionForm::Literal
    )
    .and_then(|laws| StatisticalModel::new(
        laws,
        m.summits,
        material,
        m.adhesion,
        1e-4,
        AdhesionBeyondFits::default()
    ))
    .is_err());
    let bad = SolveSettings {
        grid_step: 0.0,
        ..SolveSettings::default()
    };
    assert!(matches!(
        static_friction(&m, 1.0, &bad),
        Err(FrictionError::InvalidParameter {
            name: "grid_step",
            ..
        })
    ));
    let bad = SolveSettings {
        d_star_min: f64::NAN,
        ..SolveSettings::default()
    };
    assert!(static_friction(&m, 1.0, &bad).is_err());
}

/// The lazy grid decides most points of a compressive load by P alone, yet gives the solution of
/// the fully evaluated grid bit for bit (same brackets, same roots counted, same Brent steps):
/// the fully evaluated grid is made by asking for the pull-off load first.
#[test]
fn lazy_grid_gives_the_fully_tabulated_solution() {
    let settings = SolveSettings::default();
    let cases = [
        (model(2.0, 0.5, Model::KogutEtsion), 1e-4),
        (model(2.0, 0.5, Model::FullStick), 1e-2),
        (model(50.0, 0.5, Model::FullStick), 1e-2),
        (model(0.5, 0.5, Model::ChangEtsionBogy), 1e-6),
        (model(1.0, 0.0, Model::KogutEtsion), 1e-4),
    ];
    for (m, ratio) in cases {
        for load in [ratio * an_h(&m), 1e-3 * ratio * an_h(&m)] {
            let mut lazy = NetLoadGrid::new(&m, &settings).unwrap_or_else(|e| panic!("{e}"));
            let mut full = lazy.clone();
            full.pull_off_load(&m).unwrap_or_else(|e| panic!("{e}"));
            let a = static_friction_on_grid(&m, &mut lazy, load, &settings);
            let b = static_friction_on_grid(&m, &mut full, load, &settings);
            assert_eq!(a, b, "{:?} psi {} load {load}", m.laws, m.plasticity_index);
            let evaluated = lazy.evaluations();
            assert!(
                evaluated.net_load < evaluated.points / 2,
                "{:?} psi {}: {evaluated:?}",
                m.laws,
                m.plasticity_index
            );
            // Brute force: every grid point evaluated, sign changes counted.
            let top = 12.0 * m.summit_std_star();
            let g: Vec<f64> = (0..)
                .map(|k| -3.0 + 0.5 * f64::from(k))
                .take_while(|d| *d <= top + 0.25)
                .map(|d| net_load(&m, d).unwrap_or_else(|e| panic!("{e}")) - load)
                .collect();
            let changes = g.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
            let solved = a.unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(solved.status.roots_found, changes);
            assert!(g[0] > 0.0, "the load needs no extension of the grid");
        }
    }
    // A tensile load between pull-off and 0 needs every point (and finds two roots).
    let m = model(1.0, 0.5, Model::KogutEtsion);
    let mut lazy = NetLoadGrid::new(&m, &settings).unwrap_or_else(|e| panic!("{e}"));
    let mut full = lazy.clone();
    let pull_off = full.pull_off_load(&m).unwrap_or_else(|e| panic!("{e}"));
    let a = static_friction_on_grid(&m, &mut lazy, 0.5 * pull_off, &settings);
    let b = static_friction_on_grid(&m, &mut full, 0.5 * pull_off, &settings);
    assert_eq!(a, b);
    assert_eq!(a.map(|r| r.status.roots_found).ok(), Some(2));
}

/// The bound the lazy scan stops on: P/P_c(x′) ≤ P/P_c(x)/κ for every x′ ≤ x, checked on a dense
/// sample of x ∈ (0, 1e5] for every model (κ < 1 only for full stick, whose hand-over drops).
#[test]
fn load_laws_drop_by_at_most_their_bound() {
    for (kind, psi) in [
        (Model::KogutEtsion, 2.0),
        (Model::ChangEtsionBogy, 2.0),
        (Model::FullStick, 2.0),
        (Model::FullStick, 50.0),
    ] {
        let laws = model(psi, 0.5, kind).laws;
        let kappa = laws.load_drop_bound();
        assert!(kappa > 0.0 && kappa <= 1.0, "{kind:?}: {kappa}");
        assert_eq!(kappa < 1.0, kind == Model::FullStick, "{kind:?}: {kappa}");
        let mut running_max: f64 = 0.0;
        for i in 0..=40_000 {
            let x = 1e-3 * 10f64.powf(8.0 * f64::from(i) / 40_000.0);
            let p = laws.load_ratio(x);
            running_max = running_max.max(p);
            assert!(
                running_max <= p / kappa * (1.0 + 1e-12),
                "{kind:?} x {x}: {running_max} > {p}/{kappa}"
            );
        }
    }
}
