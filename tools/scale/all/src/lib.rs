//! Every kernel of DESIGN.md §4 for one robot, each compiled to machine code (its address
//! taken), as in a program that calls them. `../measure_all.sh` copies the robot to
//! `robot.urdf` and times the macro's expansion and `cargo build --release` of this crate.

/// Expands to the module `robot` with every kernel, on the base given first.
macro_rules! every_kernel {
    ($($base:tt)*) => {
        rne_codegen::derive_dynamics! {
            /// The robot, every kernel.
            pub mod robot {
                robot: "robot.urdf",
                $($base)*
                outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                          bias_torques, forward_dynamics, kinetic_energy, potential_energy,
                          inverse_dynamics_derivatives, forward_dynamics_derivatives,
                          mass_matrix_inverse, frame_placements, frame_jacobians,
                          frame_jacobian_dot_qd, friction_torques, regressor, base_regressor],
            }
        }
    };
}

#[cfg(feature = "floating")]
every_kernel!(base: floating,);
#[cfg(not(feature = "floating"))]
every_kernel!();

/// The address of every kernel: rustc and LLVM compile each one, as a caller would make them.
#[no_mangle]
#[inline(never)]
pub extern "C" fn kernel_addresses(out: &mut [usize; 18]) {
    *out = [
        robot::inverse_dynamics as *const () as usize,
        robot::mass_matrix as *const () as usize,
        robot::coriolis_matrix as *const () as usize,
        robot::gravity_torques as *const () as usize,
        robot::bias_torques as *const () as usize,
        robot::forward_dynamics as *const () as usize,
        robot::kinetic_energy as *const () as usize,
        robot::potential_energy as *const () as usize,
        robot::inverse_dynamics_derivatives as *const () as usize,
        robot::forward_dynamics_derivatives as *const () as usize,
        robot::mass_matrix_inverse as *const () as usize,
        robot::frame_placements as *const () as usize,
        robot::frame_jacobians as *const () as usize,
        robot::frame_jacobian_dot_qd as *const () as usize,
        robot::friction_torques as *const () as usize,
        robot::regressor as *const () as usize,
        robot::base_regressor as *const () as usize,
        robot::base_parameters as *const () as usize,
    ];
}
