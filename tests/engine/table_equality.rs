//! Compares the tables of two output folders, compute times excepted. Used by
//! `scripts/slurm-test.sh` (tables of a Slurm run against a single-process run):
//! `ASPERITY_TABLES_A=DIR ASPERITY_TABLES_B=DIR cargo test --test table_equality -- --ignored`

use crate::scale_out_common;
#[test]
#[ignore = "compares two folders named by ASPERITY_TABLES_A/_B (scripts/slurm-test.sh sets them)"]
fn same_tables_in_two_folders() {
    let folder = |var: &str| {
        std::path::PathBuf::from(
            std::env::var_os(var).unwrap_or_else(|| panic!("{var} is not set")),
        )
    };
    scale_out_common::assert_same_tables(
        &folder("ASPERITY_TABLES_A"),
        &folder("ASPERITY_TABLES_B"),
    );
}
