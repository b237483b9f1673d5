rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/negative_mass.toml",
    }
}

fn main() {}
