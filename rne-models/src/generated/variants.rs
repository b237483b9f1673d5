//! The generated variants `rne bench` compares with the built-in robots' default modules
//! ([`crate::generated`]): each robot's spec file through `derive_dynamics!` again, with one
//! scene setting changed (docs/design.md §3), for the four benchmarked kernels only (inverse
//! dynamics, mass matrix, bias torques, forward dynamics), and for the URDF robots the
//! default scene with the kernels compared with Pinocchio's (`control`).
//!
//! Per robot, a module of the robot's name holds
//! - `single`: `scalar: f32`;
//! - `zero_gravity`: `gravity: [0.0, 0.0, 0.0]`, every gravity term removed;
//! - `locked`: the first joint locked at 0 (`lock: { <first joint>: 0.0 }`): N − 1 joints;
//! - `at_rest`: `at_rest: true`, a static scene (the functions ignore `qd`);
//! - `runtime` (robots whose spec has named parameters, the TOML ones): `parameters: runtime`,
//!   every function reading a `Params` struct;
//! - `control` (the URDF robots, which `rne bench --pinocchio` sets beside Pinocchio): the
//!   control and identification kernels of docs/design.md §4 that Pinocchio also offers — the
//!   inverse- and forward-dynamics derivatives, M⁻¹, the Jacobians and J̇q̇ of every link's
//!   frame, and the joint-torque regressor — with the default scene (and `fma: true` with the
//!   crate feature `fma`, `derivatives: lanes` with the crate feature `derivative-lanes`, as
//!   the URDF robots' default modules).
//!
//! Gravity and velocities do not enter M(q), so `zero_gravity` and `at_rest` generate no mass
//! matrix: it would be the default module's.

/// The variants of one robot: see the module documentation.
macro_rules! variants {
    ($(#[$doc:meta])* $module:ident, $file:tt, $first_joint:ident $(, $runtime:ident)?
     $(; $control:ident)?) => {
        $(#[$doc])*
        pub mod $module {
            rne_codegen::derive_dynamics! {
                /// In single precision (`scalar: f32`).
                pub mod single {
                    robot: $file,
                    outputs: [inverse_dynamics, mass_matrix, bias_torques, forward_dynamics],
                    scalar: f32,
                }
            }

            rne_codegen::derive_dynamics! {
                /// Without gravity (`gravity: [0.0, 0.0, 0.0]`).
                pub mod zero_gravity {
                    robot: $file,
                    outputs: [inverse_dynamics, bias_torques, forward_dynamics],
                    gravity: [0.0, 0.0, 0.0],
                }
            }

            rne_codegen::derive_dynamics! {
                /// With the first joint locked at 0.
                pub mod locked {
                    robot: $file,
                    outputs: [inverse_dynamics, mass_matrix, bias_torques, forward_dynamics],
                    lock: { $first_joint: 0.0 },
                }
            }

            rne_codegen::derive_dynamics! {
                /// A static scene (`at_rest: true`): q̇ = 0, no Coriolis or centrifugal terms.
                pub mod at_rest {
                    robot: $file,
                    outputs: [inverse_dynamics, bias_torques, forward_dynamics],
                    at_rest: true,
                }
            }

            $(
                rne_codegen::derive_dynamics! {
                    /// With the spec's parameters read at run time (`parameters: runtime`).
                    pub mod $runtime {
                        robot: $file,
                        outputs: [inverse_dynamics, mass_matrix, bias_torques, forward_dynamics],
                        parameters: runtime,
                    }
                }
            )?

            $(
                beside_pinocchio! {
                    /// The control and identification kernels Pinocchio also offers.
                    pub mod $control {
                        robot: $file,
                        outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives,
                                  mass_matrix_inverse, frame_jacobians, frame_jacobian_dot_qd,
                                  regressor],
                    }
                }
            )?
        }
    };
}

variants!(
    /// Variants of the planar elbow (`planar-elbow`).
    planar_elbow,
    "robots/planar-elbow.toml",
    q1,
    runtime
);
variants!(
    /// Variants of the IRB 140's first three joints (`irb140-3dof`).
    irb140_3dof,
    "robots/irb140-3dof.toml",
    q1,
    runtime
);
variants!(
    /// Variants of the PUMA 560 (`puma560`); its spec has no named parameters.
    puma560,
    "robots/puma560.toml",
    q1
);
variants!(
    /// Variants of the UR5 (`ur5`); a URDF has no named parameters.
    ur5,
    "robots/ur5.urdf",
    shoulder_pan_joint;
    control
);
variants!(
    /// Variants of the Panda with its hand (`panda`); a URDF has no named parameters.
    panda,
    "robots/panda.urdf",
    panda_joint1;
    control
);
variants!(
    /// Variants of the Panda arm (`panda-arm`); a URDF has no named parameters.
    panda_arm,
    "robots/panda-arm.urdf",
    panda_joint1;
    control
);
variants!(
    /// Variants of the six-joint IRB 140 (`irb140`).
    irb140,
    "robots/irb140.toml",
    q1,
    runtime
);
