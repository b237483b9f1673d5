rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        outputs: [frame_jacobians],
        frames: [tool_flange],
    }
}

fn main() {}
