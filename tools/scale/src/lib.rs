//! A large robot's generated module, each kernel compiled to machine code (its address taken),
//! as in a program that calls it. `measure.sh` copies the robot to `robot.urdf` and times
//! `cargo build --release` of this crate (the eight dynamics kernels, floating base);
//! `measure_all.sh` times the macro and the build with every kernel (features `every-kernel`,
//! `fixed-base`).

/// The module `robot` with the given settings.
macro_rules! robot_module {
    ($($setting:tt)*) => {
        rne_codegen::derive_dynamics! {
            /// The robot.
            pub mod robot {
                robot: "robot.urdf",
                $($setting)*
            }
        }
    };
}

/// The module `robot` with every kernel and the given settings.
#[cfg(feature = "every-kernel")]
macro_rules! every_kernel {
    ($($setting:tt)*) => {
        robot_module! {
            $($setting)*
            outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                      bias_torques, forward_dynamics, kinetic_energy, potential_energy,
                      inverse_dynamics_derivatives, forward_dynamics_derivatives,
                      mass_matrix_inverse, frame_placements, frame_jacobians,
                      frame_jacobian_dot_qd, friction_torques, regressor, base_regressor],
        }
    };
}

#[cfg(not(any(feature = "every-kernel", feature = "fixed-base")))]
robot_module!(base: floating,);
#[cfg(all(not(feature = "every-kernel"), feature = "fixed-base"))]
robot_module!();
#[cfg(all(feature = "every-kernel", not(feature = "fixed-base")))]
every_kernel!(base: floating,);
#[cfg(all(feature = "every-kernel", feature = "fixed-base"))]
every_kernel!();

/// The addresses of the named kernels of `robot`.
macro_rules! addresses {
    ($($kernel:ident),* $(,)?) => {
        [$(robot::$kernel as *const () as usize),*]
    };
}

/// The address of every kernel: rustc and LLVM compile each one, as a caller would make them.
#[inline(never)]
pub fn kernel_addresses() -> Vec<usize> {
    let dynamics = addresses![
        inverse_dynamics,
        mass_matrix,
        coriolis_matrix,
        gravity_torques,
        bias_torques,
        forward_dynamics,
        kinetic_energy,
        potential_energy,
    ];
    #[cfg(feature = "every-kernel")]
    let others = addresses![
        inverse_dynamics_derivatives,
        forward_dynamics_derivatives,
        mass_matrix_inverse,
        frame_placements,
        frame_jacobians,
        frame_jacobian_dot_qd,
        friction_torques,
        regressor,
        base_regressor,
        base_parameters,
    ];
    #[cfg(not(feature = "every-kernel"))]
    let others: [usize; 0] = [];
    dynamics.into_iter().chain(others).collect()
}
