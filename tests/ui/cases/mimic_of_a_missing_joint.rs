//! With mimic joints constrained (the default), a mimic naming a joint the robot does not
//! have is an error naming the file, the joint and the field.
rne_codegen::derive_dynamics! {
    mod hand {
        robot: "specs/dangling_mimic.urdf",
    }
}

fn main() {}
