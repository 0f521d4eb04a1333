//! Prints the name of every topography reader of the registry (`READERS`), one a line, in
//! detection order: the list `scripts/fuzz-campaign.sh` fuzzes, so it never drifts from the
//! registry. `cargo run -q -p asperity-numerics --example reader_names`.

fn main() {
    for reader in asperity_numerics::surface::io::READERS {
        println!("{}", reader.name);
    }
}
