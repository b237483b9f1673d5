//! Every dynamics kernel of a large robot on a floating base, each compiled to machine code
//! (its address taken), as in a program that calls it. `measure.sh` copies the robot to
//! `robot.urdf` and times `cargo build --release` of this crate.

rne_codegen::derive_dynamics! {
    /// The robot on a floating base.
    pub mod robot {
        robot: "robot.urdf",
        base: floating,
    }
}

/// The address of every kernel: rustc and LLVM compile each one, as a caller would make them.
#[no_mangle]
#[inline(never)]
pub extern "C" fn kernel_addresses(out: &mut [usize; 8]) {
    *out = [
        robot::inverse_dynamics as *const () as usize,
        robot::mass_matrix as *const () as usize,
        robot::coriolis_matrix as *const () as usize,
        robot::gravity_torques as *const () as usize,
        robot::bias_torques as *const () as usize,
        robot::forward_dynamics as *const () as usize,
        robot::kinetic_energy as *const () as usize,
        robot::potential_energy as *const () as usize,
    ];
}
