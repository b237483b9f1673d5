rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/no_such_robot.toml",
    }
}

fn main() {}
