rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/triangle.toml",
        validation: strict,
    }
}

fn main() {}
