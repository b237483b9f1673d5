//! Shared by the reference's tests: robots built by hand or read from `tests/fixtures/`, turned
//! floating or coupled, seeded random states and error measures.

#![allow(dead_code)]

use std::path::Path;

use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rne_symbolic::model::{Base, NumericFriction, NumericLink};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{JointKind, NumericModel};

pub const G: f64 = 9.81;

/// The robot files of `tests/fixtures/` that the tests run on.
pub const FIXTURES: [&str; 5] = [
    "planar-elbow.toml",
    "puma560.toml",
    "irb140.toml",
    "ur5.urdf",
    "panda-arm.urdf",
];

/// A robot of `tests/fixtures/`, evaluated.
pub fn fixture(name: &str) -> NumericModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    read_robot(Description::file(&path), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .to_numeric()
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The stress cases' seeded values (`rne_stress::states`), included rather than depended on
/// (rne-stress builds every generated robot): the one home of `uniform`, `n` values uniform in
/// `[-bound, bound]`.
#[path = "../../../stress/src/states.rs"]
mod states;
pub use states::uniform;

/// A uniformly random unit quaternion `[x, y, z, w]`.
pub fn unit_quaternion(rng: &mut ChaCha8Rng) -> [f64; 4] {
    loop {
        let q: Vec<f64> = uniform(rng, 4, 1.0);
        let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.1 && norm <= 1.0 {
            return [q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm];
        }
    }
}

/// The rotation matrix of a unit quaternion `[x, y, z, w]`, by nalgebra (not the reference).
pub fn rotation_of(q: &[f64]) -> Matrix3<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[6], q[3], q[4], q[5]))
        .to_rotation_matrix()
        .into_inner()
}

/// A random configuration (|joints| ≤ π; a random base placement and orientation) and
/// velocity and acceleration-like vectors (entries ≤ 3) for a model with `nq`, `nv` entries.
pub fn state(rng: &mut ChaCha8Rng, model: &NumericModel) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut q = uniform(rng, model.nq(), std::f64::consts::PI);
    if model.base == Base::Floating {
        q[3..7].copy_from_slice(&unit_quaternion(rng));
    }
    (
        q,
        uniform(rng, model.nv(), 3.0),
        uniform(rng, model.nv(), 3.0),
    )
}

/// ‖a − b‖∞ / max(‖b‖∞, floor).
pub fn rel_err(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    rne_figures::relative_error_floor(a, b, floor)
}

pub fn matrix_rel_err(a: &DMatrix<f64>, b: &DMatrix<f64>, floor: f64) -> f64 {
    assert_eq!(a.shape(), b.shape());
    rel_err(a.as_slice(), b.as_slice(), floor)
}

fn diagonal(x: f64, y: f64, z: f64) -> [[f64; 3]; 3] {
    [[x, 0.0, 0.0], [0.0, y, 0.0], [0.0, 0.0, z]]
}

fn rotation_rows(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let r = nalgebra::Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(Vector3::from(axis)),
        angle,
    );
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| r[(i, j)]))
}

/// A link with every field given.
#[allow(clippy::too_many_arguments)]
pub fn link(
    name: &str,
    parent: Option<usize>,
    kind: JointKind,
    joint: Option<usize>,
    rotation: [[f64; 3]; 3],
    translation: [f64; 3],
    axis: [f64; 3],
    mass: f64,
    com: [f64; 3],
    inertia: [[f64; 3]; 3],
) -> NumericLink {
    NumericLink {
        name: name.into(),
        parent,
        kind,
        joint,
        rotation,
        translation,
        axis,
        mass,
        com,
        inertia,
        coupling: None,
        friction: None,
        armature: None,
    }
}

/// A free-flyer root body: mass 4, COM off the origin, a full inertia.
pub fn free_flyer_root() -> NumericLink {
    link(
        "torso",
        None,
        JointKind::FreeFlyer,
        None,
        diagonal(1.0, 1.0, 1.0),
        [0.0; 3],
        [0.0, 0.0, 1.0],
        4.0,
        [0.05, -0.02, 0.1],
        [[0.3, 0.01, -0.02], [0.01, 0.25, 0.03], [-0.02, 0.03, 0.2]],
    )
}

/// `model` on a floating base: a [`free_flyer_root`] in front, carrying the links that sat on
/// the world.
pub fn floating(model: &NumericModel) -> NumericModel {
    let mut links = vec![free_flyer_root()];
    links.extend(model.links.iter().map(|l| NumericLink {
        parent: Some(l.parent.map_or(0, |p| p + 1)),
        ..l.clone()
    }));
    NumericModel {
        name: format!("{}-floating", model.name),
        base: Base::Floating,
        links,
        ..model.clone()
    }
}

/// A floating robot of three bodies: a torso, a revolute arm on it and a prismatic-then-
/// revolute hand on the arm, with skewed axes and offsets so nothing is symmetric.
pub fn floating_three_body() -> NumericModel {
    let arm = link(
        "arm",
        Some(0),
        JointKind::Revolute,
        Some(0),
        rotation_rows([0.3, 0.2, 1.0], 0.4),
        [0.2, 0.1, -0.05],
        [0.0, 0.6, 0.8],
        1.5,
        [0.15, 0.0, 0.02],
        [
            [0.02, 0.001, 0.0],
            [0.001, 0.03, 0.002],
            [0.0, 0.002, 0.025],
        ],
    );
    let slider = link(
        "slider",
        Some(1),
        JointKind::Prismatic,
        Some(1),
        rotation_rows([1.0, 0.0, 0.3], -0.7),
        [0.3, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        0.8,
        [0.05, 0.01, 0.0],
        diagonal(0.004, 0.005, 0.006),
    );
    let hand = link(
        "hand",
        Some(2),
        JointKind::Revolute,
        Some(2),
        rotation_rows([0.0, 1.0, 0.2], 1.1),
        [0.1, 0.05, 0.0],
        [0.0, 0.0, 1.0],
        0.5,
        [0.0, 0.04, 0.03],
        diagonal(0.002, 0.003, 0.0025),
    );
    NumericModel {
        name: "floating-three-body".into(),
        gravity: [0.0, 0.0, -G],
        base: Base::Floating,
        links: vec![free_flyer_root(), arm, slider, hand],
        joint_names: vec!["q1".into(), "q2".into(), "q3".into()],
    }
}

/// A single free body: the free-flyer root alone.
pub fn free_body() -> NumericModel {
    NumericModel {
        name: "free-body".into(),
        gravity: [0.3, -0.5, -G],
        base: Base::Floating,
        links: vec![free_flyer_root()],
        joint_names: vec![],
    }
}

/// One mimic constraint: joint variable `follower` of the uncoupled model becomes
/// `multiplier · q[leader] + offset`.
#[derive(Clone, Copy, Debug)]
pub struct Mimic {
    pub follower: usize,
    pub leader: usize,
    pub multiplier: f64,
    pub offset: f64,
}

/// `model` with `mimic`'s follower coupled to its leader (the follower's variable removed, later
/// variables renumbered), and the map from the coupled model's state to the uncoupled one's.
pub fn coupled(model: &NumericModel, mimic: Mimic) -> (NumericModel, Coupling) {
    let renumber = |k: usize| if k > mimic.follower { k - 1 } else { k };
    let links = model
        .links
        .iter()
        .map(|l| match l.joint {
            Some(k) if k == mimic.follower => NumericLink {
                joint: Some(renumber(mimic.leader)),
                coupling: Some((mimic.multiplier, mimic.offset)),
                ..l.clone()
            },
            Some(k) => NumericLink {
                joint: Some(renumber(k)),
                ..l.clone()
            },
            None => l.clone(),
        })
        .collect();
    let mut joint_names = model.joint_names.clone();
    joint_names.remove(mimic.follower);
    let coupled = NumericModel {
        name: format!("{}-coupled", model.name),
        links,
        joint_names,
        ..model.clone()
    };
    let base = model.nv() - model.dof();
    let (nv_full, nv) = (model.nv(), coupled.nv());
    let mut jacobian = DMatrix::zeros(nv_full, nv);
    for r in 0..nv_full {
        if r == base + mimic.follower {
            jacobian[(r, base + renumber(mimic.leader))] = mimic.multiplier;
        } else {
            jacobian[(
                r,
                if r < base {
                    r
                } else {
                    base + renumber(r - base)
                },
            )] = 1.0;
        }
    }
    let coupling = Coupling {
        jacobian,
        q_base: model.nq() - model.dof(),
        follower: mimic.follower,
        leader: renumber(mimic.leader),
        multiplier: mimic.multiplier,
        offset: mimic.offset,
    };
    (coupled, coupling)
}

/// The map from a coupled model's state to its uncoupled model's: `q_full` with the follower's
/// coordinate `m q_leader + offset`, `v_full = J v`, `τ = Jᵀ τ_full`, `M = Jᵀ M_full J`.
pub struct Coupling {
    pub jacobian: DMatrix<f64>,
    q_base: usize,
    follower: usize,
    leader: usize,
    multiplier: f64,
    offset: f64,
}

impl Coupling {
    pub fn full_q(&self, q: &[f64]) -> Vec<f64> {
        let b = self.q_base;
        let mut full = q.to_vec();
        full.insert(
            b + self.follower,
            self.multiplier * q[b + self.leader] + self.offset,
        );
        full
    }

    pub fn full_v(&self, v: &[f64]) -> Vec<f64> {
        (&self.jacobian * DVector::from_column_slice(v))
            .as_slice()
            .to_vec()
    }
}

/// Friction and armature on every revolute or prismatic link: distinct values per link.
pub fn with_friction_and_armature(model: &NumericModel) -> NumericModel {
    let links = model
        .links
        .iter()
        .enumerate()
        .map(|(i, l)| match l.kind {
            JointKind::Revolute | JointKind::Prismatic => NumericLink {
                friction: Some(NumericFriction {
                    viscous: 0.1 + 0.05 * i as f64,
                    coulomb: 0.3 + 0.1 * i as f64,
                    offset: 0.02 * i as f64 - 0.05,
                }),
                armature: Some(0.01 + 0.02 * i as f64),
                ..l.clone()
            },
            _ => l.clone(),
        })
        .collect();
    NumericModel {
        links,
        ..model.clone()
    }
}

/// `model` with a massive tool fixed behind its last link (two fixed links deep, rotated and
/// offset) and a massive plate fixed to the world, which moves nothing.
pub fn with_fixed_payload(model: &NumericModel) -> NumericModel {
    let last = model.links.len() - 1;
    let fixed = |name: &str, parent: Option<usize>, mass: f64| {
        link(
            name,
            parent,
            JointKind::Fixed,
            None,
            rotation_rows([0.2, -0.5, 1.0], 0.9),
            [0.05, -0.1, 0.2],
            [0.0, 0.0, 1.0],
            mass,
            [0.02, 0.03, -0.04],
            [
                [0.01, 0.002, 0.0],
                [0.002, 0.02, 0.001],
                [0.0, 0.001, 0.015],
            ],
        )
    };
    let mut links = model.links.clone();
    links.push(fixed("flange", Some(last), 0.7));
    links.push(fixed("tool", Some(last + 1), 1.2));
    if model.base == Base::Fixed {
        links.push(fixed("plate", None, 5.0));
    }
    NumericModel {
        name: format!("{}-payload", model.name),
        links,
        ..model.clone()
    }
}
