rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/massless_tool.toml",
        outputs: [inverse_dynamics, forward_dynamics],
    }
}

fn main() {}
