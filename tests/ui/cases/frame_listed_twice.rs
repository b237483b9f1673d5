rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        outputs: [frame_placements],
        frames: [upper, "upper"],
    }
}

fn main() {}
