rne_codegen::derive_dynamics! {
    mod arm {
        robot: [1],
    }
}

fn main() {}
