//! Readers for X3P, SDF, SUR, PLU, text/CSV and npy against the reference values of the shared
//! measured-topography folder (its SOURCES.md / reference_values.json), and against the small
//! fixtures in `tests/data/`.
//!
//! Tolerances: statistics relative 1e-6 (the acceptance criterion; the references are printed
//! with ≥ 10 significant digits and both are sums of ≤ 1.2 M doubles, so summation-order
//! differences are ~1e-12); spacings relative 1e-6 (several files store them as float32,
//! whose rounding, ~6e-8, is well inside); SDF ramps absolute 1e-13 m as sdfio asserts.

use crate::common;
use crate::readers_a_common;
use asperity_numerics::surface::io::{detect_format, read_topography, TopographyData};
use readers_a_common::{
    assert_rel, fixture, plain_stats, read_areal, rms_gradient, rq_profiles_along_x,
};

const RTOL: f64 = 1e-6;

/// One file's expected values (lengths in metres).
struct Reference {
    file: &'static str,
    format: &'static str,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    missing: usize,
    sq: f64,
    sa: f64,
    sz: f64,
    ssk: f64,
    sku: f64,
}

/// From reference_values.json (`own_reader` / SurfaceTopography_1.27.1 entries, which agree;
/// lengths converted to metres).
const REFERENCES: &[Reference] = &[
    Reference {
        file: "x3p/x3p-2.x3p",
        format: "x3p",
        nx: 650,
        ny: 650,
        dx: 8.29767313942749e-05 / 650.0,
        dy: 2.044783737930349e-04 / 650.0,
        missing: 0,
        sq: 7.728033273597876e-08,
        sa: 6.195465568874848e-08,
        sz: 5.543362e-07,
        ssk: -0.34678860126701305,
        sku: 2.9419337352647124,
    },
    Reference {
        file: "x3p/KautschukInfiniteFocus.x3p",
        format: "x3p",
        nx: 860,
        ny: 634,
        dx: 2.279984215e-6,
        dy: 2.279794519e-6,
        missing: 5296,
        sq: 3.3988718108632547e-06,
        sa: 2.70527700244401e-06,
        sz: 2.568441050243564e-05,
        ssk: 0.7326648190406716,
        sku: 3.686634344428373,
    },
    Reference {
        file: "x3p/SkiInfiniteFocus.x3p",
        format: "x3p",
        nx: 1197,
        ny: 940,
        dx: 3.678887926e-6,
        dy: 3.680270397e-6,
        missing: 4272,
        sq: 1.815496570404691e-05,
        sa: 1.5237409943544703e-05,
        sz: 8.423632243648171e-05,
        ssk: -0.8729936397866374,
        sku: 2.543470052596036,
    },
    Reference {
        file: "x3p/sample-land.x3p",
        format: "x3p",
        nx: 1836,
        ny: 512,
        dx: 1.29e-6,
        dy: 1.29e-6,
        missing: 101_532,
        sq: 3.4336498051108274e-05,
        sa: 2.984713491842267e-05,
        sz: 0.0001348340738331899,
        ssk: -0.416386757249843,
        sku: 1.913999211461846,
    },
    Reference {
        file: "x3p/x3ptools-2024/sample-land.x3p",
        format: "x3p",
        nx: 918,
        ny: 256,
        dx: 2.58e-6,
        dy: 2.58e-6,
        missing: 25_292,
        sq: 3.433427489069121e-05,
        sa: 2.9843114766790535e-05,
        sz: 0.00013197206135373563,
        ssk: -0.41734619297235037,
        sku: 1.9146041820511843,
    },
    Reference {
        file: "x3p/ISO5436-sample1.x3p",
        format: "x3p",
        nx: 4,
        ny: 4,
        dx: 0.016016,
        dy: 0.016016,
        missing: 1,
        sq: 0.6105091545422601,
        sa: 0.5523542851143993,
        sz: 1.8559645973442502,
        ssk: -0.4458189493605808,
        sku: 1.7297401837536397,
    },
    Reference {
        file: "x3p/ISO5436-sample4_bin.x3p",
        format: "x3p",
        nx: 4,
        ny: 4,
        dx: 0.016016,
        dy: 0.016016,
        missing: 1,
        sq: 0.6105375773311037,
        sa: 0.5524000000000001,
        sz: 1.856,
        ssk: -0.44516800025638353,
        sku: 1.7291364943365013,
    },
    Reference {
        file: "sdf/sdf-1.sdf",
        format: "sdf",
        nx: 7,
        ny: 4,
        dx: 1e-6,
        dy: 1e-6,
        missing: 0,
        sq: 1.3602897289488263e-08,
        sa: 1.1580127551020412e-08,
        sz: 5.093e-08,
        ssk: -0.643046063033514,
        sku: 2.5772730752046806,
    },
    Reference {
        file: "sdf/mm11_iso1_ascii_int32.sdf",
        format: "sdf",
        nx: 30,
        ny: 20,
        dx: 1e-6,
        dy: 1e-6,
        missing: 1,
        sq: 1.7299607528330785e-07,
        sa: 1.497980774858487e-07,
        sz: 5.99e-07,
        ssk: -0.0014490274966289351,
        sku: 1.801712259520758,
    },
    Reference {
        file: "sdf/mm11_iso2_ascii_binary64.sdf",
        format: "sdf",
        nx: 30,
        ny: 20,
        dx: 1e-6,
        dy: 1e-6,
        missing: 1,
        sq: 1.7299607528330783e-07,
        sa: 1.497980774858487e-07,
        sz: 5.98999995977e-07 + 4.023e-15,
        ssk: -0.001449027496629681,
        sku: 1.8017122595207586,
    },
    Reference {
        file: "sur/sur-2.sur",
        format: "sur",
        nx: 563,
        ny: 484,
        dx: 3.4840002190321684e-06,
        dy: 3.4840002190321684e-06,
        missing: 117,
        sq: 1.7517881243588178e-08,
        sa: 1.2011706033181184e-08,
        sz: 1.4760000172486798e-06,
        ssk: -14.669065424197282,
        sku: 745.9080170949865,
    },
    Reference {
        file: "sur/sur-3.sur",
        format: "sur",
        nx: 512,
        ny: 512,
        dx: 0.151319552 / 512.0,
        dy: 0.151319552 / 512.0,
        missing: 233_009,
        sq: 1.113199427e-03,
        sa: 0.0007435424456250447,
        sz: 0.0069923498022428365,
        ssk: -2.4322119586070703,
        sku: 9.695426116797899,
    },
    Reference {
        file: "plu/plu-1.plu",
        format: "plu",
        nx: 768,
        ny: 576,
        dx: 1274.880066e-6 / 768.0,
        dy: 956.160049e-6 / 576.0,
        missing: 0,
        sq: 2.8343909876348845e-06,
        sa: 2.4518279358018025e-06,
        sz: 10.015625e-6,
        ssk: -0.0010801476421814847,
        sku: 1.8084336138023225,
    },
    Reference {
        file: "txt/matrix-2.txt",
        format: "text",
        nx: 650,
        ny: 650,
        dx: 3.69862e-7,
        dy: 3.69862e-7,
        missing: 0,
        sq: 2.772235040274007e-07,
        sa: 2.1595002114748556e-07,
        sz: 3.4023004581841994e-06,
        ssk: -0.15803666866421756,
        sku: 4.404074004113232,
    },
    Reference {
        file: "txt/matrix-3.txt",
        format: "text",
        nx: 256,
        ny: 256,
        dx: 10e-6 / 256.0,
        dy: 10e-6 / 256.0,
        missing: 0,
        sq: 3.522291875019874e-08,
        sa: 2.622809150586104e-08,
        sz: 4.0883e-07,
        ssk: -0.3997884387665554,
        sku: 5.661688105122327,
    },
    Reference {
        file: "txt/matrix-4.txt",
        format: "text",
        nx: 75,
        ny: 305,
        dx: 3.69862e-7,
        dy: 3.69862e-7,
        missing: 0,
        sq: 1.1745891510991089e-07,
        sa: 9.740592805732852e-08,
        sz: 5.897958694348e-07,
        ssk: 0.06695492442602732,
        sku: 2.3413210724026015,
    },
];

#[test]
fn every_areal_file_reproduces_its_reference_values() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    for r in REFERENCES {
        let path = dir.join(r.file);
        let bytes = std::fs::read(&path).expect("reference file must exist");
        assert_eq!(
            detect_format(&path, &bytes).map(|f| f.name),
            Some(r.format),
            "{}: format detection",
            r.file
        );
        let map = read_areal(&path);
        assert_eq!((map.nx(), map.ny()), (r.nx, r.ny), "{}: grid", r.file);
        assert_rel(&format!("{} dx", r.file), map.dx(), r.dx, RTOL);
        assert_rel(&format!("{} dy", r.file), map.dy(), r.dy, RTOL);
        assert_eq!(map.missing_count(), r.missing, "{}: missing points", r.file);
        let s = plain_stats(map.heights().iter());
        assert_eq!(s.n_valid, r.nx * r.ny - r.missing);
        assert_rel(&format!("{} Sq", r.file), s.sq, r.sq, RTOL);
        assert_rel(&format!("{} Sa", r.file), s.sa, r.sa, RTOL);
        assert_rel(&format!("{} Sz", r.file), s.sz, r.sz, RTOL);
        assert_rel(&format!("{} Ssk", r.file), s.ssk, r.ssk, RTOL);
        assert_rel(&format!("{} Sku", r.file), s.sku, r.sku, RTOL);
    }
}

/// Values asserted by SurfaceTopography's own tests (rtol 1e-6 there): the profile Rq and the
/// rms gradient, which also checks that dx and dy are not swapped (x3p-2 has dx ≠ dy).
#[test]
fn upstream_asserted_profile_and_gradient_values() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let cases: &[(&str, Option<f64>, Option<f64>)] = &[
        (
            "x3p/x3p-2.x3p",
            Some(7.628063407071483e-08),
            Some(0.062070073998443276),
        ),
        ("plu/plu-1.plu", Some(2.8338952607410217e-06), None),
        ("txt/matrix-2.txt", None, Some(0.35152685030417763)),
        ("txt/matrix-3.txt", None, Some(0.19235602282848963)),
        (
            "txt/matrix-4.txt",
            Some(7.198047156165951e-08),
            Some(0.06776316911544318),
        ),
    ];
    for &(file, rq, grad) in cases {
        let map = read_areal(&dir.join(file));
        if let Some(rq) = rq {
            assert_rel(&format!("{file} Rq"), rq_profiles_along_x(&map), rq, RTOL);
        }
        if let Some(g) = grad {
            assert_rel(&format!("{file} rms gradient"), rms_gradient(&map), g, RTOL);
        }
    }
    // Asserted physical sizes.
    let sizes: &[(&str, f64, f64)] = &[
        ("x3p/x3p-2.x3p", 8.29767313942749e-05, 2.044783737930349e-04),
        ("sur/sur-3.sur", 0.151319552, 0.151319552),
        ("plu/plu-1.plu", 1274.880066e-6, 956.160049e-6),
        ("txt/matrix-4.txt", 2.773965e-05, 1.1280791e-04),
    ];
    for &(file, lx, ly) in sizes {
        let (sx, sy) = read_areal(&dir.join(file)).size();
        assert_rel(&format!("{file} Lx"), sx, lx, RTOL);
        assert_rel(&format!("{file} Ly"), sy, ly, RTOL);
    }
}

/// sdfio asserts z[i, j] = (30·i + j)·1e-9 m (i = profile) to 1e-13 m for the MountainsMap
/// exports; the `BAD` point is profile 0, point 29.
fn assert_mm11_ramp(map: &asperity_numerics::surface::HeightMap, what: &str) {
    for ((i, j), &z) in map.heights().indexed_iter() {
        if (i, j) == (0, 29) {
            assert!(z.is_nan(), "{what}: BAD point must be NaN");
        } else {
            let expected = (30 * i + j) as f64 * 1e-9;
            assert!((z - expected).abs() <= 1e-13, "{what}[{i},{j}] = {z:e}");
        }
    }
}

#[test]
fn sdf_ramps_and_binary_fixtures() {
    let iso1 = read_areal(&fixture("mm11_iso1_ascii_int32.sdf"));
    assert_mm11_ramp(&iso1, "iso1 ascii");
    let binary = read_areal(&fixture("mm11_iso2_binary_f64.sdf"));
    assert_mm11_ramp(&binary, "iso2 binary");
    if let Some(dir) = common::data_dir() {
        let iso2 = read_areal(&dir.join("sdf/mm11_iso2_ascii_binary64.sdf"));
        assert_mm11_ramp(&iso2, "iso2 ascii");
        // The binary fixture holds the same doubles: bit-identical heights.
        assert_eq!(
            iso2.heights()
                .iter()
                .map(|z| z.to_bits())
                .collect::<Vec<_>>(),
            binary
                .heights()
                .iter()
                .map(|z| z.to_bits())
                .collect::<Vec<_>>()
        );
    }
    // int32 binary of the ISO example: values × 1e-11 m equal the ASCII values × 1e-6 m.
    let ascii = read_areal(&fixture("sdf-1.sdf"));
    let bin = read_areal(&fixture("sdf-1_binary_int32.sdf"));
    assert_eq!((bin.nx(), bin.ny(), bin.dx()), (7, 4, 1e-6));
    for (a, b) in ascii.heights().iter().zip(bin.heights()) {
        // Both are decimal values with 5 digits, rounded once each: relative 1e-15.
        assert!((a - b).abs() <= 1e-15 * a.abs(), "{a:e} vs {b:e}");
    }
}

#[test]
fn x3p_fixture_with_mask_subfolder_and_integer_heights() {
    let path = fixture("tiny_int32_masked.x3p");
    let t = read_topography(&path).expect("fixture must read");
    assert_eq!(t.metadata["revision"], "ISO5436 \u{2013} 2000");
    assert_eq!(t.metadata["x3p_root_element"], "ISO5436");
    assert_eq!(t.metadata["y_offset_m"], "0.001");
    let TopographyData::Areal(map) = t.data else {
        panic!("expected an areal map")
    };
    assert_eq!((map.nx(), map.ny(), map.dx(), map.dy()), (3, 2, 2e-6, 5e-6));
    let h = map.heights();
    assert!(h[[0, 1]].is_nan(), "masked point must be NaN");
    // z = raw · 1e-9 + 1e-6, one rounding each: absolute 1e-21 m.
    for ((iy, ix), raw) in [((0, 0), 10.0), ((0, 2), 30.0), ((1, 2), -60.0)] {
        assert!((h[[iy, ix]] - (raw * 1e-9 + 1e-6)).abs() < 1e-21);
    }
}

/// The Dektak stylus CSV is a non-uniform line scan (x rounded to 0.1 µm).
#[test]
fn dektak_csv_is_a_non_uniform_line_scan() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let path = dir.join("csv/dektak-1.csv");
    let t = read_topography(&path).expect("dektak must read");
    let TopographyData::Line(line) = t.data else {
        panic!("dektak must be a line scan")
    };
    assert_eq!(line.x.len(), 9600);
    assert_rel("dektak length", line.x[9599] - line.x[0], 1499.8e-6, RTOL);
    let steps: Vec<f64> = line.x.windows(2).map(|w| w[1] - w[0]).collect();
    let (lo, hi) = steps.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &s| {
        (lo.min(s), hi.max(s))
    });
    assert!(
        hi - lo > 0.05e-6,
        "spacing must stay non-uniform ({lo:e}..{hi:e})"
    );
    let s = plain_stats(line.z.iter());
    assert_rel("dektak Sq (points)", s.sq, 4.764232930211046e-6, RTOL);
    assert_rel("dektak Sa", s.sa, 4.11319267084375e-6, RTOL);
    assert_rel("dektak Sz", s.sz, 16.590449999999997e-6, RTOL);
    assert_rel("dektak Ssk", s.ssk, -0.049093018769378105, RTOL);
    assert_rel("dektak Sku", s.sku, 1.8238747696828659, RTOL);
}

#[test]
fn npy_round_trip_of_a_real_map() {
    // Writes x3p-2 (or the SDF fixture when the shared data is absent) as big-endian f8 npy
    // and reads it back: same heights, spacing flagged as assumed.
    let source = common::data_dir()
        .map(|d| d.join("x3p/x3p-2.x3p"))
        .unwrap_or_else(|| fixture("sdf-1.sdf"));
    let map = read_areal(&source);
    let dict = format!(
        "{{'descr': '>f8', 'fortran_order': False, 'shape': ({}, {}), }}",
        map.ny(),
        map.nx()
    );
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((dict.len() as u16).to_le_bytes());
    bytes.extend(dict.as_bytes());
    for z in map.heights() {
        bytes.extend(z.to_be_bytes());
    }
    let t = asperity_numerics::surface::io::parse_topography(std::path::Path::new("a.npy"), &bytes)
        .expect("npy must parse");
    assert_eq!(
        t.spacing,
        asperity_numerics::surface::io::ScaleSource::Assumed
    );
    let TopographyData::Areal(back) = t.data else {
        panic!("expected an areal map")
    };
    assert_eq!(back.heights(), map.heights());
    assert_eq!((back.dx(), back.dy()), (1.0, 1.0));
}
