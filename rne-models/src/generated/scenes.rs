//! The thesis's robots generated for the scenes chapter 6 simulates besides the full arms
//! (which are [`super::planar_elbow`] and [`super::irb140_3dof`]): the arms with g(q) removed
//! from the model (the thesis's gravity compensation, (6.33) and (6.53)), and the IRB 140 with
//! joints 1 and 2 locked (the joint-3 pendulum of section 6.3.3); beyond the thesis, the planar
//! elbow with its joints' viscous friction in the model and the quadruped floating in zero
//! gravity. Each module's `Model` is the
//! [`Dynamics`](rne_codegen::Dynamics) a simulation integrates; the kernels are straight-line
//! code over `[f64; N]`, so a step of the integrators never allocates.

rne_codegen::derive_dynamics! {
    /// The planar elbow with gravity removed from the model: M q̈ + C q̇ = u, (6.33).
    pub mod planar_elbow_weightless {
        robot: "robots/planar-elbow.toml",
        outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                  kinetic_energy, potential_energy],
        gravity: [0.0, 0.0, 0.0],
    }
}

rne_codegen::derive_dynamics! {
    /// The IRB 140's first three joints with gravity removed from the model: (6.53).
    pub mod irb140_weightless {
        robot: "robots/irb140-3dof.toml",
        outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                  kinetic_energy, potential_energy],
        gravity: [0.0, 0.0, 0.0],
    }
}

rne_codegen::derive_dynamics! {
    /// The IRB 140 with joints 1 and 2 locked at 0 (x₁ = … = x₄ = 0): link 3 alone swings
    /// as a pendulum about joint 3, section 6.3.3 (figures 6.16 and 6.17).
    pub mod irb140_joint3 {
        robot: "robots/irb140-3dof.toml",
        outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                  kinetic_energy, potential_energy],
        lock: { q1: 0.0, q2: 0.0 },
    }
}

rne_codegen::derive_dynamics! {
    /// The planar elbow with the viscous joint friction fv = 1.5 N·m·s/rad of its spec in the
    /// model (`friction: include`): M q̈ + C q̇ + g + fv q̇ = u, the thesis's damped double
    /// pendulum (6.31) with the damping Kd = 1.5 of (6.30) as a property of the joints.
    pub mod planar_elbow_viscous {
        robot: "robots/planar-elbow.toml",
        outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity_torques,
                  kinetic_energy, potential_energy, friction_torques],
        friction: include,
    }
}

rne_codegen::derive_dynamics! {
    /// rne-models' quadruped (`robots/quadruped.urdf`: a 6 kg trunk with four two-joint legs)
    /// on a floating base in zero gravity: a free-flying robot that moves only its joints, the
    /// scene of the `quadruped-in-space` scenario, whose total momentum the Lie-group
    /// variational integrator conserves. NQ = 7 + 8, NV = 6 + 8.
    pub mod quadruped_space {
        robot: "robots/quadruped.urdf",
        outputs: [mass_matrix, coriolis_matrix, gravity_torques, forward_dynamics,
                  kinetic_energy, potential_energy],
        base: floating,
        gravity: [0.0, 0.0, 0.0],
    }
}
