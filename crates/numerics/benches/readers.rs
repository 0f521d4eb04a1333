//! Reading the largest measured topography file (SkiInfiniteFocus.x3p, 1197 × 940 float32,
//! 4.1 MB zip) and the largest text matrix (matrix-2.txt, 650 × 650, 3.9 MB), from memory.
//!
//! Run: `cargo bench -p asperity-numerics --bench readers` (needs the shared data folder; set
//! `ASPERITY_TEST_DATA` if it is not at `../shared/data/topography`).

use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};

fn data_dir() -> Option<PathBuf> {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::env::var_os("ASPERITY_TEST_DATA")
        .map(PathBuf::from)
        .into_iter()
        .chain(
            crate_dir
                .ancestors()
                .map(|dir| dir.join("shared/data/topography")),
        )
        .find(|d| d.join("SOURCES.md").is_file())
}

fn bench_readers(c: &mut Criterion) {
    let Some(dir) = data_dir() else {
        eprintln!("shared topography data not found: nothing to benchmark");
        return;
    };
    for file in [
        "x3p/SkiInfiniteFocus.x3p",
        "txt/matrix-2.txt",
        "sur/sur-2.sur",
    ] {
        let path = dir.join(file);
        let bytes = std::fs::read(&path).expect("benchmark file must exist");
        c.bench_function(&format!("read {file}"), |b| {
            b.iter(|| {
                asperity_numerics::surface::io::parse_topography(
                    &path,
                    std::hint::black_box(&bytes),
                )
                .expect("file must parse")
            })
        });
    }
}

criterion_group! {
    name = readers;
    config = Criterion::default().sample_size(20);
    targets = bench_readers
}
criterion_main!(readers);
