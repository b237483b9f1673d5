//! The Coriolis matrix C(q, q̇) by the recursive algorithm of S. Echeandia and P. M. Wensing,
//! "Numerical methods to compute the Coriolis matrix and Christoffel symbols for rigid-body
//! systems", J. Comput. Nonlinear Dynam. 16(9), 2021 (arXiv:2010.01033), Algorithm 1,
//! written on expressions in the body frames of [`crate::model`] with 3-vectors.
//!
//! With J_k the Jacobian of body k, V_k = J_k q̇ its velocity and I_k its spatial inertia,
//! all in world axes,
//!
//! ```text
//! C = Σ_k J_kᵀ (I_k J̇_k + B(I_k, V_k) J_k),   B(I, V) = ½ (V×* I + (I V)×̄ − I V×),
//! ```
//!
//! with `(f)×̄ W = W ×* f`. B is the body-level factorisation whose Christoffel symbols are
//! symmetric, so on joint coordinates this C is the Christoffel C of the thesis's section 6.4
//! (C_ij = Σ_k Γ_ijk q̇_k, `christoffel.rs`, checked equal in the tests); Ṁ − 2C is skew
//! because B + Bᵀ = İ. Column j of J_k (k carried by j's joint) is the joint's motion
//! subspace S_j, whose world-frame rate is Ṡ_j = V_j × S_j; summing each body into the
//! composite body of every joint that carries it turns the sum into one pass from each joint
//! towards the root, O(N d) for N bodies and a tree of depth d, instead of the O(N³)
//! Christoffel symbols:
//!
//! ```text
//! C_ij = S_iᵀ F1,   C_ji = Ṡ_iᵀ F2 + S_iᵀ F3     (link i = link j or an ancestor of it)
//! F1 = I^C_j Ṡ_j + B^C_j S_j,   F2 = I^C_j S_j,   F3 = (B^C_j)ᵀ S_j
//! ```
//!
//! `B^C_j = Σ_k B(I_k, V_k)` over j's composite body is not accumulated as a 6×6 matrix:
//! with `D_k = V_k×* I_k − I_k V_k×` and the composite momentum `h^C_j = Σ_k I_k V_k`,
//! `B^C_j = ½ D^C_j + ½ (h^C_j)×̄`, and `D^C_j S_j + I^C_j Ṡ_j = V_j ×* F2 + İ^C_j S_j`, where
//! İ^C_j, the rate of j's composite inertia as its own joints move it in B_j, is a spatial
//! inertia with zero mass (nine numbers, carried to the parent like the composite inertia).
//! Hence F1 = ½ (T + U), F3 = ½ (T − U) with `T = V_j ×* F2 + İ^C_j S_j` and
//! `U = I^C_j Ṡ_j + S_j ×* h^C_j`.
//!
//! On a floating base the free-flyer's six columns are its body axes and its velocity the
//! body-frame twist, and the same sum gives a C for which C v is the bias less gravity and
//! Ṁ − 2C is skew; as the base velocities are not the rates of
//! coordinates, C(v) w − C(w) v is then `M [v_b × w_b; 0]` rather than zero (the base rows
//! of a torsion-free connection in the body frame). With mimic joints the follower's column
//! enters with its multiplier (C ← Jᵀ C J, J constant).

use super::crba::{self, Column, Composite};
use super::energy;
use super::inertial_parameters::BodyParameters;
use crate::expr::{ExprGraph, Id, Vec3};
use crate::model::{Link, RobotModel};
use crate::motion::{JointMotion, LinkCoordinate, LinkPlacement};

/// A spatial motion vector in body axes: angular velocity and velocity of the body origin.
#[derive(Copy, Clone, Debug)]
struct Twist {
    angular: Vec3,
    linear: Vec3,
}

/// A spatial force in body axes: moment about the body origin and force.
#[derive(Copy, Clone, Debug)]
struct Wrench {
    moment: Vec3,
    force: Vec3,
}

impl Twist {
    /// The unit motion of a motion-subspace column.
    fn of_column(g: &mut ExprGraph, column: &Column) -> Twist {
        let zero = g.zero_vec();
        if column.angular {
            Twist {
                angular: column.axis,
                linear: zero,
            }
        } else {
            Twist {
                angular: zero,
                linear: column.axis,
            }
        }
    }

    /// `self × other` of motions: `(ω₁ × ω₂, ω₁ × v₂ + v₁ × ω₂)`.
    fn cross(self, g: &mut ExprGraph, other: Twist) -> Twist {
        let angular = g.cross(self.angular, other.angular);
        let a = g.cross(self.angular, other.linear);
        let b = g.cross(self.linear, other.angular);
        Twist {
            angular,
            linear: g.vadd(a, b),
        }
    }

    /// `self ×* f`: `(ω × n + v × f, ω × f)`.
    fn cross_force(self, g: &mut ExprGraph, f: Wrench) -> Wrench {
        let a = g.cross(self.angular, f.moment);
        let b = g.cross(self.linear, f.force);
        Wrench {
            moment: g.vadd(a, b),
            force: g.cross(self.angular, f.force),
        }
    }

    /// The power `ω · n + v · f`.
    fn dot(self, g: &mut ExprGraph, f: Wrench) -> Id {
        let a = g.dot(self.angular, f.moment);
        let b = g.dot(self.linear, f.force);
        g.add(a, b)
    }
}

impl Wrench {
    fn add(self, g: &mut ExprGraph, other: Wrench) -> Wrench {
        Wrench {
            moment: g.vadd(self.moment, other.moment),
            force: g.vadd(self.force, other.force),
        }
    }

    /// The same force in the parent's axes, about the parent's origin:
    /// `f' = R f`, `n' = R n + s × f'`.
    fn to_parent(self, g: &mut ExprGraph, placement: &LinkPlacement) -> Wrench {
        let force = placement.to_parent(g, self.force);
        let rotated = placement.to_parent(g, self.moment);
        let shift = g.cross(placement.attachment, force);
        Wrench {
            moment: g.vadd(rotated, shift),
            force,
        }
    }
}

/// The spatial inertia `body` (mass m, first moment h, inertia I about the origin) times a
/// twist: `n = I ω + h × v`, `f = m v + ω × h`.
fn apply(g: &mut ExprGraph, body: &Composite, t: Twist) -> Wrench {
    let i_omega = g.mat_vec(&body.inertia, t.angular);
    let h_v = g.cross(body.first_moment, t.linear);
    let m_v = g.vscale(body.mass, t.linear);
    let omega_h = g.cross(t.angular, body.first_moment);
    Wrench {
        moment: g.vadd(i_omega, h_v),
        force: g.vadd(m_v, omega_h),
    }
}

/// The rate of the spatial inertia `body` as it moves with twist `w` = (ω, v) in its own
/// axes (`w ×* I − I w×`), again a spatial inertia: mass 0, `ḣ = ω × h + m v`,
/// `İ = ω× I − I ω× + 2 (h · v) 1 − v hᵀ − h vᵀ`.
fn rate(g: &mut ExprGraph, body: &Composite, w: Twist) -> Composite {
    let omega_h = g.cross(w.angular, body.first_moment);
    let m_v = g.vscale(body.mass, w.linear);
    let first_moment = g.vadd(omega_h, m_v);
    // K = ω× I column by column; ω× I − I ω× = K + Kᵀ (I symmetric).
    let columns: [Vec3; 3] = std::array::from_fn(|c| {
        let column = [body.inertia[0][c], body.inertia[1][c], body.inertia[2][c]];
        g.cross(w.angular, column)
    });
    let h_dot_v = g.dot(body.first_moment, w.linear);
    let two = g.constant(2.0);
    let diagonal = g.mul(two, h_dot_v);
    let mut inertia = body.inertia;
    for a in 0..3 {
        for b in a..3 {
            let rotation = g.add(columns[b][a], columns[a][b]);
            let x = g.mul(w.linear[a], body.first_moment[b]);
            let y = g.mul(body.first_moment[a], w.linear[b]);
            let xy = g.add(x, y);
            let mut entry = g.sub(rotation, xy);
            if a == b {
                entry = g.add(entry, diagonal);
            }
            inertia[a][b] = entry;
            inertia[b][a] = entry;
        }
    }
    Composite {
        mass: g.zero(),
        first_moment,
        inertia,
    }
}

/// The sum of two spatial inertias.
fn sum(g: &mut ExprGraph, a: &Composite, b: &Composite) -> Composite {
    let mut inertia = a.inertia;
    for r in 0..3 {
        for c in r..3 {
            let entry = g.add(a.inertia[r][c], b.inertia[r][c]);
            inertia[r][c] = entry;
            inertia[c][r] = entry;
        }
    }
    Composite {
        mass: g.add(a.mass, b.mass),
        first_moment: g.vadd(a.first_moment, b.first_moment),
        inertia,
    }
}

/// The quantities of every link that the passes of [`coriolis_matrix`] share.
struct Tree<'a> {
    links: &'a [Link],
    /// The motion-subspace columns of each link's joint.
    columns: &'a [Vec<Column>],
    placements: &'a [LinkPlacement],
    /// The composite inertia I^C of each link.
    composites: &'a [Composite],
    /// The velocity V of each link.
    velocities: &'a [Twist],
}

/// C(q, q̇) of `model` at `motion` (NV × NV, row-major), by the recursion of the module
/// documentation.
pub fn coriolis_matrix(
    model: &mut RobotModel,
    motion: &JointMotion,
    bodies: Option<&[BodyParameters]>,
) -> Vec<Vec<Id>> {
    let nv = model.state_layout().nv();
    let columns = crba::columns(model);
    let g = &mut model.graph;
    let links = &model.links;
    let placements = LinkPlacement::all(g, links, motion);
    let composites = crba::composite_bodies(g, links, &placements, bodies);
    let velocities: Vec<Twist> = energy::link_velocities(g, links, motion)
        .into_iter()
        .map(|(angular, linear)| Twist { angular, linear })
        .collect();
    let tree = Tree {
        links,
        columns: &columns,
        placements: &placements,
        composites: &composites,
        velocities: &velocities,
    };
    let (momenta, rates) = momenta_and_rates(g, &tree, motion, bodies);
    let motions = column_motions(g, &tree);
    let mut terms = Terms {
        half: g.constant(0.5),
        entries: vec![vec![Vec::new(); nv]; nv],
    };
    for j in 0..links.len() {
        for b in 0..columns[j].len() {
            let body = (momenta[j], &rates[j]);
            let forces = column_forces(g, &tree, j, body, motions[j][b]);
            push_column(g, &tree, &motions, &mut terms, (j, b), forces);
        }
    }
    terms
        .entries
        .into_iter()
        .map(|row| row.into_iter().map(|entry| g.sum(entry)).collect())
        .collect()
}

/// The composite momenta h^C and the composite inertia rates İ^C of every link, leaves first.
fn momenta_and_rates(
    g: &mut ExprGraph,
    tree: &Tree,
    motion: &JointMotion,
    bodies: Option<&[BodyParameters]>,
) -> (Vec<Wrench>, Vec<Composite>) {
    let links = tree.links;
    let n = links.len();
    let mut momenta: Vec<Wrench> = links
        .iter()
        .zip(tree.velocities)
        .enumerate()
        .map(|(i, (link, &v))| {
            let body = match bodies {
                Some(bodies) => bodies[i],
                None => BodyParameters::of_link(g, link),
            };
            let body = Composite {
                mass: body.mass,
                first_moment: body.first_moment,
                inertia: body.inertia,
            };
            apply(g, &body, v)
        })
        .collect();
    let zero = g.zero();
    let at_rest = Composite {
        mass: zero,
        first_moment: [zero; 3],
        inertia: [[zero; 3]; 3],
    };
    let mut rates = vec![at_rest; n];
    for i in (0..n).rev() {
        let Some(p) = links[i].parent else { continue };
        let moved = momenta[i].to_parent(g, &tree.placements[i]);
        momenta[p] = momenta[p].add(g, moved);
        let mut own = rates[i];
        if let (Some(c), Some(column)) = (
            LinkCoordinate::of(g, &links[i], motion),
            tree.columns[i].first(),
        ) {
            let unit = Twist::of_column(g, column);
            let w = Twist {
                angular: g.vscale(c.qd, unit.angular),
                linear: g.vscale(c.qd, unit.linear),
            };
            let moving = rate(g, &tree.composites[i], w);
            own = sum(g, &own, &moving);
        }
        let moved = crba::to_parent(g, &own, &tree.placements[i]);
        rates[p] = sum(g, &rates[p], &moved);
    }
    (momenta, rates)
}

/// Each column's S and Ṡ = V × S, link by link.
fn column_motions(g: &mut ExprGraph, tree: &Tree) -> Vec<Vec<(Twist, Twist)>> {
    tree.columns
        .iter()
        .zip(tree.velocities)
        .map(|(link_columns, &v)| {
            link_columns
                .iter()
                .map(|column| {
                    let s = Twist::of_column(g, column);
                    (s, v.cross(g, s))
                })
                .collect()
        })
        .collect()
}

/// The forces of one column S_j of link j, in j's axes: F2 = I^C_j S_j,
/// T = V_j ×* F2 + İ^C_j S_j and U = I^C_j Ṡ_j + S_j ×* h^C_j.
struct ColumnForces {
    f2: Wrench,
    t: Wrench,
    u: Wrench,
}

/// [`ColumnForces`] of the column with motion `(s, s_dot)` of link `j`, whose composite
/// momentum is `momentum` and composite inertia rate `rate`.
fn column_forces(
    g: &mut ExprGraph,
    tree: &Tree,
    j: usize,
    (momentum, rate): (Wrench, &Composite),
    (s, s_dot): (Twist, Twist),
) -> ColumnForces {
    let f2 = apply(g, &tree.composites[j], s);
    let transported = tree.velocities[j].cross_force(g, f2);
    let moving = apply(g, rate, s);
    let t = transported.add(g, moving);
    let inertial = apply(g, &tree.composites[j], s_dot);
    let gyroscopic = s.cross_force(g, momentum);
    let u = inertial.add(g, gyroscopic);
    ColumnForces { f2, t, u }
}

/// The terms of C, per entry, before they are summed.
struct Terms {
    half: Id,
    entries: Vec<Vec<Vec<Id>>>,
}

impl Terms {
    /// Adds `entry` to C at (`row`, `column`), times the mimic multipliers of both.
    fn push(&mut self, g: &mut ExprGraph, row: &Column, column: &Column, entry: Id) {
        let mut entry = entry;
        for m in [row.multiplier, column.multiplier].into_iter().flatten() {
            entry = g.mul(m, entry);
        }
        self.entries[row.index][column.index].push(entry);
    }
}

/// The entries of column `b` of link `j` with the columns of j itself (C_ij = S_iᵀ F1) and of
/// each of its ancestors i (C_ij = S_iᵀ F1 and C_ji = Ṡ_iᵀ F2 + S_iᵀ F3), the forces carried
/// to each ancestor's axes on the way to the root.
fn push_column(
    g: &mut ExprGraph,
    tree: &Tree,
    motions: &[Vec<(Twist, Twist)>],
    terms: &mut Terms,
    (j, b): (usize, usize),
    forces: ColumnForces,
) {
    let cb = &tree.columns[j][b];
    let ColumnForces {
        mut f2,
        mut t,
        mut u,
    } = forces;
    for (a, ca) in tree.columns[j].iter().enumerate() {
        let sa = motions[j][a].0;
        let (ta, ua) = (sa.dot(g, t), sa.dot(g, u));
        let f1 = g.add(ta, ua);
        let entry = g.mul(terms.half, f1);
        terms.push(g, ca, cb, entry);
    }
    let mut i = j;
    while let Some(p) = tree.links[i].parent {
        t = t.to_parent(g, &tree.placements[i]);
        u = u.to_parent(g, &tree.placements[i]);
        f2 = f2.to_parent(g, &tree.placements[i]);
        i = p;
        for (a, ca) in tree.columns[i].iter().enumerate() {
            let (sa, sa_dot) = motions[i][a];
            let (ta, ua) = (sa.dot(g, t), sa.dot(g, u));
            let f1 = g.add(ta, ua);
            let upper = g.mul(terms.half, f1);
            terms.push(g, ca, cb, upper);
            let f3 = g.sub(ta, ua);
            let f3 = g.mul(terms.half, f3);
            let rate_term = sa_dot.dot(g, f2);
            let lower = g.add(rate_term, f3);
            terms.push(g, cb, ca, lower);
        }
    }
}
