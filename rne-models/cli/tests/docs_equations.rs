//! The equations docs/ shows are what `rne show` prints today: the compact program of the
//! Panda's mass matrix in docs/equations/ is regenerated and compared byte for byte, so a
//! change of the optimiser or of the printer shows in the docs' diff.

mod common;
use common::rne;

/// The committed file `docs/equations/NAME`, from the repository's root.
fn committed(name: &str) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/equations/").to_owned() + name;
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn the_panda_mass_matrix_program_in_the_docs_is_what_rne_show_prints() {
    let printed = rne(&["show", "panda", "--what", "M", "--compact"]).expect("rne show runs");
    assert!(
        printed == committed("panda-mass-matrix.txt"),
        "docs/equations/panda-mass-matrix.txt is stale: regenerate it with \
         `rne show panda --what M --compact > docs/equations/panda-mass-matrix.txt`"
    );
}
