//! The kernels whose throughput `run.sh` analyses, each behind a function of its own that
//! is never inlined (`mca_*`), so that its body in the assembly is the kernel alone: UR5's
//! inverse dynamics as `rne bench` times it built for the machine (rne-models' feature
//! `fma`: `fma: true`) and without fused multiply-add, and the generic UR5 and Panda arm inverse dynamics and mass matrix
//! of the lanes bench (`tests/benches/lanes.rs`) in `f64` and in `F64x4`, and the batch
//! helper's own work around the Panda arm's `F64x4` mass matrix.

use rne_codegen::F64x4;

rne_codegen::derive_dynamics! {
    mod ur5_fused {
        robot: "../../rne-models/robots/ur5.urdf",
        outputs: [inverse_dynamics],
        fma: true,
    }
}

rne_codegen::derive_dynamics! {
    mod ur5_plain {
        robot: "../../rne-models/robots/ur5.urdf",
        outputs: [inverse_dynamics],
    }
}

rne_codegen::derive_dynamics! {
    mod ur5 {
        robot: "../../tests/fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix],
        scalar: generic,
    }
}

rne_codegen::derive_dynamics! {
    mod panda {
        robot: "../../rne-models/robots/panda-arm.urdf",
        outputs: [inverse_dynamics, mass_matrix],
        scalar: generic,
    }
}

/// One kernel call, its arguments and result in memory.
macro_rules! wrapper {
    ($name:ident, $module:ident :: $kernel:ident, $t:ty, $n:literal, ($($arg:ident),*), $out:ty) => {
        #[inline(never)]
        pub fn $name($($arg: &[$t; $n],)* out: &mut $out) {
            *out = $module::$kernel($($arg),*);
        }
    };
}

wrapper!(
    mca_ur5_id_fused,
    ur5_fused::inverse_dynamics,
    f64,
    6,
    (q, qd, qdd),
    [f64; 6]
);
wrapper!(
    mca_ur5_id_plain,
    ur5_plain::inverse_dynamics,
    f64,
    6,
    (q, qd, qdd),
    [f64; 6]
);
wrapper!(
    mca_ur5_id_f64,
    ur5::inverse_dynamics,
    f64,
    6,
    (q, qd, qdd),
    [f64; 6]
);
wrapper!(
    mca_ur5_id_f64x4,
    ur5::inverse_dynamics,
    F64x4,
    6,
    (q, qd, qdd),
    [F64x4; 6]
);
wrapper!(mca_ur5_m_f64, ur5::mass_matrix, f64, 6, (q), [[f64; 6]; 6]);
wrapper!(
    mca_ur5_m_f64x4,
    ur5::mass_matrix,
    F64x4,
    6,
    (q),
    [[F64x4; 6]; 6]
);
wrapper!(
    mca_panda_id_f64,
    panda::inverse_dynamics,
    f64,
    7,
    (q, qd, qdd),
    [f64; 7]
);
wrapper!(
    mca_panda_id_f64x4,
    panda::inverse_dynamics,
    F64x4,
    7,
    (q, qd, qdd),
    [F64x4; 7]
);
wrapper!(
    mca_panda_m_f64,
    panda::mass_matrix,
    f64,
    7,
    (q),
    [[f64; 7]; 7]
);
wrapper!(
    mca_panda_m_f64x4,
    panda::mass_matrix,
    F64x4,
    7,
    (q),
    [[F64x4; 7]; 7]
);

rne_codegen::derive_dynamics! {
    mod panda_batched {
        robot: "../../rne-models/robots/panda-arm.urdf",
        outputs: [mass_matrix],
        scalar: generic,
    }
}

/// The kernel the batch helper calls below: a function of its own, so that the helper's
/// body holds the helper's work alone (and `panda::mass_matrix` stays inlined in
/// `mca_panda_m_f64x4`, its only caller).
#[inline(never)]
fn batched_mass_matrix(q: &[F64x4; 7]) -> [[F64x4; 7]; 7] {
    panda_batched::mass_matrix(q)
}

/// The batch helper's own work for one group of four states of the Panda arm's mass matrix
/// in `F64x4`: gathering the angles into lanes, and scattering the result to the four states
/// (the kernel is a call here; `panda_m_f64x4` is its body).
#[inline(never)]
pub fn mca_panda_m_batch(states: &[[f64; 7]; 4], out: &mut [[[f64; 7]; 7]; 4]) {
    rne_codegen::batch::evaluate(states, out, batched_mass_matrix);
}
