//! Generated modules of a URDF with a mimic joint: by default the follower has no variable
//! (URDF semantics) and the kernels are the free model's seen through the chain rule;
//! `mimic: free` keeps it as a joint of its own (Pinocchio's default).

rne_codegen::derive_dynamics! {
    /// Mimic followers constrained (the default).
    mod constrained {
        robot: "fixtures/robots/gripper-mimic.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
    }
}

rne_codegen::derive_dynamics! {
    /// Every follower its own joint.
    mod free {
        robot: "fixtures/robots/gripper-mimic.urdf",
        outputs: [inverse_dynamics, mass_matrix],
        mimic: free,
    }
}

#[test]
fn a_constrained_follower_has_no_variable_and_enters_through_the_chain_rule() {
    assert_eq!(constrained::JOINTS, ["wrist", "finger_left"]);
    assert_eq!(free::JOINTS, ["wrist", "finger_left", "finger_right"]);
    // J maps (wrist, left) to (wrist, left, right = left).
    for k in 0..20 {
        let x = 0.3 * k as f64;
        let (q, qd, qdd) = ([x.sin(), 0.01 * x], [x.cos(), -0.2], [0.5, 0.1 * x]);
        let lift = |v: [f64; 2]| [v[0], v[1], v[1]];
        let tau_free = free::inverse_dynamics(&lift(q), &lift(qd), &lift(qdd));
        let tau = constrained::inverse_dynamics(&q, &qd, &qdd);
        assert!((tau[0] - tau_free[0]).abs() < 1e-12);
        assert!((tau[1] - (tau_free[1] + tau_free[2])).abs() < 1e-12);
        let m_free = free::mass_matrix(&lift(q));
        let m = constrained::mass_matrix(&q);
        let reduced = m_free[1][1] + 2.0 * m_free[1][2] + m_free[2][2];
        assert!((m[1][1] - reduced).abs() < 1e-12);
        assert!((m[0][1] - (m_free[0][1] + m_free[0][2])).abs() < 1e-12);
        let back = constrained::forward_dynamics(&q, &qd, &tau);
        assert!((back[0] - qdd[0]).abs() < 1e-10 && (back[1] - qdd[1]).abs() < 1e-10);
    }
}
