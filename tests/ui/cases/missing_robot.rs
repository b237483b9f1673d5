rne_codegen::derive_dynamics! {
    mod arm {
        outputs: [inverse_dynamics],
    }
}

fn main() {}
