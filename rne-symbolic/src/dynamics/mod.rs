//! Taking the Newton–Euler torques apart: M(q), C(q, q̇), g(q), the bias, the energies and
//! forward dynamics, each built on demand into the model's expression graph (3.1).

mod aba;
mod aba_frames;
mod articulated_inertia;
mod base_dynamics;
pub mod base_parameters;
mod christoffel;
mod coriolis;
mod crba;
pub mod derivatives;
mod energy;
pub mod friction;
pub mod inertial_parameters;
mod kinematics;
mod lane_partials;
mod ldlt;
pub mod regressor;

use crate::expr::{Differentiator, ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::model::{Frame, RobotModel, StateLayout};
use crate::motion::{quaternion_rotation, BaseMotion, JointMotion};
use crate::newton_euler::{newton_euler, JointReaction, NewtonEuler};
use base_parameters::BaseParameters;
use inertial_parameters::BodyParameters;
pub use lane_partials::{Direction, LanePartials, LANES};

/// A matrix of expressions, row-major.
pub type Matrix = Vec<Vec<Id>>;

/// The [`OpCount::cost`](crate::OpCount::cost) of the state Jacobians `(dq, dv)`, shared
/// subexpressions counted once: what the choice of their sweep compares.
fn jacobians_cost(g: &ExprGraph, dq: &Matrix, dv: &Matrix) -> usize {
    g.op_count(&[dq.concat(), dv.concat()].concat()).cost()
}

/// The nodes `qdd` as the values of the acceleration symbols q̈₀, q̈₁, … (the forward
/// dynamics' derivatives put FD in for q̈, [`SymbolicDynamics::forward_dynamics_derivatives`]).
fn acceleration_values(qdd: &[Id]) -> Vec<(Symbol, Id)> {
    qdd.iter()
        .enumerate()
        .map(|(k, &a)| (Symbol::Acceleration(k as u16), a))
        .collect()
}

/// The rows of expressions `rows` with `values` substituted ([`ExprGraph::substitute`]).
fn substitute_rows(g: &mut ExprGraph, rows: &[Vec<Id>], values: &[(Symbol, Id)]) -> Matrix {
    let mut entries = g.substitute(&rows.concat(), values).into_iter();
    rows.iter()
        .map(|row| entries.by_ref().take(row.len()).collect())
        .collect()
}

/// States the base parameters are found from ([`SymbolicDynamics::base_parameters`]): each
/// gives NV equations, and a body has at most 10 + 4 parameters per joint variable, so 40
/// states stack at least twice as many equations as there are parameters.
pub const BASE_PARAMETER_SAMPLES: usize = 40;

/// The largest number of joint variables for which [`SymbolicDynamics::coriolis_matrix`] also
/// tries the Christoffel symbols (O(n³) of them: 1728 at 12, built in milliseconds).
pub const CHRISTOFFEL_UP_TO: usize = 12;

/// The dynamics of a robot, M(q) q̈ + C(q, q̇) q̇ + g(q) = u (3.1), as expressions.
///
/// Each quantity is built the first time it is asked for, into [`SymbolicDynamics::model`]'s
/// graph, and cached: a code generator that needs only the mass matrix never builds the
/// Christoffel symbols. Fixed joints are merged into their parents first.
#[derive(Clone, Debug)]
pub struct SymbolicDynamics {
    /// The model (fixed links merged) whose graph holds every expression built so far.
    pub model: RobotModel,
    at_rest: bool,
    friction: bool,
    full: Option<NewtonEuler>,
    mass_matrix: Option<Vec<Vec<Id>>>,
    gravity_torques: Option<Vec<Id>>,
    bias_torques: Option<Vec<Id>>,
    coriolis_matrix: Option<Vec<Vec<Id>>>,
    kinetic_energy: Option<Id>,
    potential_energy: Option<Id>,
    forward_dynamics: Option<Vec<Id>>,
    /// The LᵀDL factor of the mass matrix, shared by forward dynamics, M⁻¹ and the
    /// forward-dynamics derivatives.
    mass_matrix_factor: Option<ldlt::LtdlFactor>,
    mass_matrix_inverse: Option<Vec<Vec<Id>>>,
    inverse_dynamics_derivatives: Option<(Matrix, Matrix)>,
    /// The sweep the state Jacobians of the torques are built by, once known
    /// ([`Self::with_derivative_sweep`], [`Self::inverse_dynamics_derivatives`]).
    derivative_sweep: Option<derivatives::Sweep>,
    frames: Vec<Frame>,
    /// The bodies' standard parameters when they replace the links' inertias
    /// ([`Self::with_standard_parameters`]).
    bodies: Option<Vec<BodyParameters>>,
}

impl SymbolicDynamics {
    /// Prepares the dynamics of `model`.
    pub fn new(model: &RobotModel) -> SymbolicDynamics {
        let mut model = model.clone();
        let frames = model.frames();
        SymbolicDynamics {
            model: model.merge_fixed_links(),
            frames,
            at_rest: false,
            friction: false,
            full: None,
            mass_matrix: None,
            gravity_torques: None,
            bias_torques: None,
            coriolis_matrix: None,
            kinetic_energy: None,
            potential_energy: None,
            forward_dynamics: None,
            mass_matrix_factor: None,
            mass_matrix_inverse: None,
            inverse_dynamics_derivatives: None,
            derivative_sweep: None,
            bodies: None,
        }
    }

    /// The dynamics of a scene where the robot moves slowly enough that q̇ = 0 (a static or
    /// quasi-static scene): every joint velocity is the constant 0, so Coriolis and
    /// centrifugal terms vanish and τ = M(q) q̈ + g(q). Must be chosen before anything is built.
    pub fn at_rest(mut self) -> SymbolicDynamics {
        self.at_rest = true;
        self
    }

    /// The dynamics with joint friction ([`friction`]) in the inverse and forward dynamics and
    /// friction columns in the regressor (`friction: include`); without, friction is only
    /// available through [`Self::friction_torques`]. Must be chosen before anything is built.
    pub fn with_friction(mut self) -> SymbolicDynamics {
        self.friction = true;
        self
    }

    /// The dynamics whose torque derivatives are built by `sweep` without trying the other:
    /// the sweep [`Self::derivative_sweep`] reported for dynamics of the same model and scene,
    /// whose torques have the same expression DAG and so the same costs, is the one
    /// [`Self::inverse_dynamics_derivatives`] would choose.
    pub fn with_derivative_sweep(mut self, sweep: derivatives::Sweep) -> SymbolicDynamics {
        self.derivative_sweep = Some(sweep);
        self
    }

    /// The sweep the torque derivatives were built by, once they have been.
    pub fn derivative_sweep(&self) -> Option<derivatives::Sweep> {
        self.derivative_sweep
    }

    /// Whether friction is part of the inverse and forward dynamics.
    pub fn includes_friction(&self) -> bool {
        self.friction
    }

    /// Number of joint variables (NDOF).
    pub fn dof(&self) -> usize {
        self.model.dof()
    }

    /// Where the joint variables and the free-flyer sit in q and v.
    pub fn layout(&self) -> StateLayout {
        self.model.state_layout()
    }

    /// The symbols of a velocity-sized vector (q̇, q̈ or the generalised forces): one per entry
    /// of v. Velocities are the constant 0 in a scene at rest.
    fn velocity_symbols(&mut self, make: fn(u16) -> Symbol) -> Vec<Id> {
        if self.at_rest && make(0) == Symbol::Velocity(0) {
            return self.zeros();
        }
        (0..self.layout().nv())
            .map(|k| self.model.graph.symbol(make(k as u16)))
            .collect()
    }

    /// For each entry of v, the position symbol it is the rate of (`None` for the free-flyer's
    /// body-frame velocities).
    fn rate_positions(&self) -> Vec<Option<Symbol>> {
        let layout = self.layout();
        (0..layout.nv())
            .map(|k| {
                (k >= layout.v_offset())
                    .then(|| Symbol::Position((k - layout.v_offset() + layout.q_offset()) as u16))
            })
            .collect()
    }

    /// Zeros of the length of v.
    fn zeros(&mut self) -> Vec<Id> {
        vec![self.model.graph.zero(); self.layout().nv()]
    }

    /// The motion whose positions are the configuration symbols and whose velocities and
    /// accelerations are `v` and `a` (velocity-sized: the free-flyer's six first).
    fn motion(&mut self, v: Vec<Id>, a: Vec<Id>) -> JointMotion {
        let layout = self.layout();
        let g = &mut self.model.graph;
        let q: Vec<Id> = (0..layout.ndof)
            .map(|k| g.symbol(Symbol::Position((layout.q_offset() + k) as u16)))
            .collect();
        let base = layout.floating.then(|| {
            let p: [Id; 7] = std::array::from_fn(|k| g.symbol(Symbol::Position(k as u16)));
            BaseMotion {
                rotation: quaternion_rotation(g, [p[3], p[4], p[5], p[6]]),
                position: [p[0], p[1], p[2]],
                velocity: std::array::from_fn(|k| v[k]),
                acceleration: std::array::from_fn(|k| a[k]),
            }
        });
        let offset = layout.v_offset();
        JointMotion {
            q,
            qd: v[offset..].to_vec(),
            qdd: a[offset..].to_vec(),
            base,
        }
    }

    fn run(&mut self, qd: Vec<Id>, qdd: Vec<Id>, gravity: Vec3) -> NewtonEuler {
        let motion = self.motion(qd, qdd);
        match &self.bodies {
            Some(bodies) => {
                inertial_parameters::inverse_dynamics(&mut self.model, &motion, gravity, bodies)
            }
            None => newton_euler(&mut self.model, &motion, gravity),
        }
    }

    fn full(&mut self) -> &NewtonEuler {
        if self.full.is_none() {
            let qd = self.velocity_symbols(Symbol::Velocity);
            let qdd = self.velocity_symbols(Symbol::Acceleration);
            let gravity = self.model.gravity;
            self.full = Some(self.run(qd, qdd, gravity));
        }
        self.full.as_ref().expect("just built")
    }

    /// τ(q, q̇, q̈): the joint torques of the full recursion, plus the joint friction when it
    /// is included.
    pub fn inverse_dynamics(&mut self) -> Vec<Id> {
        let torques = self.full().torques.clone();
        self.plus_friction(torques)
    }

    /// `torques` plus the joint friction when it is included.
    fn plus_friction(&mut self, torques: Vec<Id>) -> Vec<Id> {
        if !self.friction {
            return torques;
        }
        let friction = self.friction_torques();
        let g = &mut self.model.graph;
        torques
            .iter()
            .zip(&friction)
            .map(|(&t, &f)| g.add(t, f))
            .collect()
    }

    /// τ_f(q̇) = f_v q̇ + f_c sign(q̇) + offset of every entry of v ([`friction`]), whether or not
    /// friction is included in the dynamics.
    pub fn friction_torques(&mut self) -> Vec<Id> {
        let qd = self.velocity_symbols(Symbol::Velocity);
        friction::friction_torques(&mut self.model, &qd)
    }

    /// u − τ_f(q̇): the generalised forces that accelerate the robot, with friction included.
    fn driving_forces(&mut self) -> Vec<Id> {
        let u = self.velocity_symbols(Symbol::Force);
        if !self.friction {
            return u;
        }
        let friction = self.friction_torques();
        let g = &mut self.model.graph;
        u.iter()
            .zip(&friction)
            .map(|(&u, &f)| g.sub(u, f))
            .collect()
    }

    /// The joint reactions f_i, τ_i of every link (body frames), from the full recursion.
    pub fn joint_reactions(&mut self) -> Vec<JointReaction> {
        self.full().reactions.clone()
    }

    /// M(q), row-major and symmetric (the same `Id` at (i, j) and (j, i)), by the
    /// composite-rigid-body algorithm (`crba`): the coefficients of q̈ in (3.1).
    pub fn mass_matrix(&mut self) -> Vec<Vec<Id>> {
        if let Some(m) = &self.mass_matrix {
            return m.clone();
        }
        let zeros = self.zeros();
        let motion = self.motion(zeros.clone(), zeros);
        let m = crba::mass_matrix(&mut self.model, &motion, self.bodies.as_deref());
        self.mass_matrix = Some(m.clone());
        m
    }

    /// g(q): the torques of the recursion with q̇ = q̈ = 0.
    pub fn gravity_torques(&mut self) -> Vec<Id> {
        if let Some(g) = &self.gravity_torques {
            return g.clone();
        }
        let (qd, qdd, gravity) = (self.zeros(), self.zeros(), self.model.gravity);
        let g = self.run(qd, qdd, gravity).torques;
        self.gravity_torques = Some(g.clone());
        g
    }

    /// C(q, q̇) q̇ + g(q): the torques of the recursion with q̈ = 0.
    pub fn bias_torques(&mut self) -> Vec<Id> {
        if let Some(b) = &self.bias_torques {
            return b.clone();
        }
        let qd = self.velocity_symbols(Symbol::Velocity);
        let (qdd, gravity) = (self.zeros(), self.model.gravity);
        let b = self.run(qd, qdd, gravity).torques;
        self.bias_torques = Some(b.clone());
        b
    }

    /// The Christoffel C(q, q̇), for which Ṁ − 2C is skew-symmetric, by the O(N d) recursion
    /// of Echeandia and Wensing (2021) (module `coriolis`). On a fixed base with at most
    /// [`CHRISTOFFEL_UP_TO`] joint variables the same matrix is also built from its Christoffel
    /// symbols ([`Self::christoffel_coriolis_matrix`]), and the construction with fewer
    /// operations is kept: on small arms the symbols, shared through the graph, are cheaper.
    pub fn coriolis_matrix(&mut self) -> Vec<Vec<Id>> {
        if let Some(c) = &self.coriolis_matrix {
            return c.clone();
        }
        // The symbols first, so that a model keeping them gets the graph (and the emitted
        // code) it had before the recursion existed.
        let christoffel = (!self.layout().floating && self.layout().nv() <= CHRISTOFFEL_UP_TO)
            .then(|| self.christoffel_coriolis_matrix());
        let mut c = self.recursive_coriolis_matrix();
        if let Some(christoffel) = christoffel {
            let g = &self.model.graph;
            if g.op_count(&christoffel.concat()).cost() < g.op_count(&c.concat()).cost() {
                c = christoffel;
            }
        }
        self.coriolis_matrix = Some(c.clone());
        c
    }

    /// The Christoffel C(q, q̇) by the recursion of Echeandia and Wensing (2021)
    /// (module `coriolis`), whatever the model's size.
    pub fn recursive_coriolis_matrix(&mut self) -> Vec<Vec<Id>> {
        let qd = self.velocity_symbols(Symbol::Velocity);
        let zeros = self.zeros();
        let motion = self.motion(qd, zeros);
        coriolis::coriolis_matrix(&mut self.model, &motion, self.bodies.as_deref())
    }

    /// The same C from its definition, C_ij = Σ_k Γ_ijk q̇_k with the O(n³) Christoffel symbols
    /// of ∂M/∂q: an oracle for [`Self::coriolis_matrix`], on a fixed base only (the base
    /// velocities of a floating base are not the rates of coordinates).
    ///
    /// # Panics
    /// On a floating base.
    pub fn christoffel_coriolis_matrix(&mut self) -> Vec<Vec<Id>> {
        let m = self.mass_matrix();
        let qd = self.velocity_symbols(Symbol::Velocity);
        let positions = self.rate_positions();
        christoffel::coriolis_matrix(&mut self.model.graph, &m, &qd, &positions)
    }

    /// Ṁ(q, q̇) = Σ_k ∂M/∂q_k q̇_k.
    pub fn mass_matrix_derivative(&mut self) -> Vec<Vec<Id>> {
        let m = self.mass_matrix();
        let qd = self.velocity_symbols(Symbol::Velocity);
        let positions = self.rate_positions();
        christoffel::time_derivative(&mut self.model.graph, &m, &qd, &positions)
    }

    /// Kinetic energy ½ Σ (m_i v_ci · v_ci + ω_iᵀ I_i ω_i), from the link velocities.
    pub fn kinetic_energy(&mut self) -> Id {
        if let Some(t) = self.kinetic_energy {
            return t;
        }
        let qd = self.velocity_symbols(Symbol::Velocity);
        let zeros = self.zeros();
        let motion = self.motion(qd, zeros);
        let t = match &self.bodies {
            Some(bodies) => inertial_parameters::kinetic_energy(&mut self.model, &motion, bodies),
            None => energy::kinetic_energy(&mut self.model, &motion),
        };
        self.kinetic_energy = Some(t);
        t
    }

    /// Potential energy −Σ m_i g_0 · p_ci, zero with every COM at the base origin.
    pub fn potential_energy(&mut self) -> Id {
        if let Some(v) = self.potential_energy {
            return v;
        }
        let zeros = self.zeros();
        let motion = self.motion(zeros.clone(), zeros);
        let v = match &self.bodies {
            Some(bodies) => inertial_parameters::potential_energy(&mut self.model, &motion, bodies),
            None => energy::potential_energy(&mut self.model, &motion),
        };
        self.potential_energy = Some(v);
        v
    }

    /// q̈ = M(q)⁻¹ (u − C(q, q̇) q̇ − g(q)) (6.2), with u the `Force` symbols (less the
    /// friction when it is included), through a symbolic LᵀDL factorisation of M that keeps
    /// M's structural zeros.
    pub fn forward_dynamics(&mut self) -> Vec<Id> {
        if let Some(f) = &self.forward_dynamics {
            return f.clone();
        }
        // M before the bias, so that the nodes keep the order the kernel has always had.
        self.mass_matrix();
        let bias = self.bias_torques();
        let u = self.driving_forces();
        let g = &mut self.model.graph;
        let rhs: Vec<Id> = u.iter().zip(&bias).map(|(&u, &b)| g.sub(u, b)).collect();
        let factor = self.mass_matrix_factor();
        let qdd = factor.solve(&mut self.model.graph, &rhs);
        self.forward_dynamics = Some(qdd.clone());
        qdd
    }

    /// The LᵀDL factor of M, built the first time it is asked for.
    fn mass_matrix_factor(&mut self) -> ldlt::LtdlFactor {
        if let Some(factor) = &self.mass_matrix_factor {
            return factor.clone();
        }
        let m = self.mass_matrix();
        let factor = ldlt::LtdlFactor::new(&mut self.model.graph, &m);
        self.mass_matrix_factor = Some(factor.clone());
        factor
    }

    /// M(q)⁻¹, symmetric (one `Id` per pair), from the LᵀDL factorisation of M.
    pub fn mass_matrix_inverse(&mut self) -> Vec<Vec<Id>> {
        if let Some(m) = &self.mass_matrix_inverse {
            return m.clone();
        }
        let factor = self.mass_matrix_factor();
        let inverse = derivatives::inverse(&mut self.model.graph, &factor);
        self.mass_matrix_inverse = Some(inverse.clone());
        inverse
    }

    /// (∂τ/∂q, ∂τ/∂q̇), NV × NV each, row i the derivatives of τ_i; ∂/∂q in the tangent space
    /// ([`derivatives`]). ∂τ/∂q̈ is M.
    pub fn inverse_dynamics_derivatives(&mut self) -> (Matrix, Matrix) {
        if let Some(d) = &self.inverse_dynamics_derivatives {
            return d.clone();
        }
        let tau = self.inverse_dynamics();
        let (dq, dv) = self.state_jacobians(&tau);
        self.inverse_dynamics_derivatives = Some((dq.clone(), dv.clone()));
        (dq, dv)
    }

    /// The [`OpCount::cost`](crate::OpCount::cost) of the torque derivatives (built first
    /// when they are not yet, by the sweep [`Self::with_derivative_sweep`] fixed or the
    /// cheaper): with a sweep fixed each way on two copies of the same dynamics, what
    /// [`derivatives::Sweep::cheaper`] compares to choose, the two built at the same time.
    pub fn inverse_dynamics_derivatives_cost(&mut self) -> usize {
        let (dq, dv) = self.inverse_dynamics_derivatives();
        jacobians_cost(&self.model.graph, &dq, &dv)
    }

    /// [`Self::inverse_dynamics_derivatives_cost`] by forward sweeps, or `None` as soon as the
    /// derivatives built so far cost more than `bound` says
    /// ([`derivatives::forward_state_jacobians_within`]); then the dynamics' graph holds a part
    /// of the sweeps and is of no further use.
    pub fn forward_derivatives_cost_within(
        &mut self,
        bound: &mut dyn FnMut() -> Option<usize>,
    ) -> Option<usize> {
        let tau = self.inverse_dynamics();
        let layout = self.layout();
        let g = &mut self.model.graph;
        let (dq, dv) = derivatives::forward_state_jacobians_within(g, &tau, layout, bound)?;
        let cost = jacobians_cost(g, &dq, &dv);
        self.derivative_sweep = Some(derivatives::Sweep::Forward);
        self.inverse_dynamics_derivatives = Some((dq, dv));
        Some(cost)
    }

    /// The state Jacobians of the torques `tau` ([`derivatives::state_jacobians`]).
    ///
    /// Built by forward sweeps (one per symbol) and by reverse sweeps (one per torque), one
    /// after the other in the graph (the first taken out while the second is tried,
    /// [`ExprGraph::split_off`]); the one of lower [`OpCount::cost`](crate::OpCount::cost) is
    /// kept, the forward sweep on a tie. A sweep known beforehand
    /// ([`Self::with_derivative_sweep`]) is built alone; the one chosen is remembered.
    fn state_jacobians(&mut self, tau: &[Id]) -> (Matrix, Matrix) {
        let layout = self.layout();
        let g = &mut self.model.graph;
        let (sweep, dq, dv) = match self.derivative_sweep {
            Some(sweep) => {
                let (dq, dv) = derivatives::state_jacobians(g, tau, layout, sweep);
                (sweep, dq, dv)
            }
            None => {
                let build = |sweep| {
                    move |g: &mut ExprGraph| {
                        let (dq, dv) = derivatives::state_jacobians(g, tau, layout, sweep);
                        (jacobians_cost(g, &dq, &dv), (dq, dv))
                    }
                };
                let (sweep, (dq, dv)) = cheaper_sweep(
                    g,
                    build(derivatives::Sweep::Forward),
                    build(derivatives::Sweep::Reverse),
                );
                (sweep, dq, dv)
            }
        };
        self.derivative_sweep = Some(sweep);
        (dq, dv)
    }

    /// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) at q̈ = FD(q, q̇, u), with u the `Force` symbols:
    /// ∂q̈/∂x = −M⁻¹ ∂τ/∂x, ∂τ/∂x the torques' derivatives at constant q̈
    /// ([`Self::inverse_dynamics_derivatives`]) with FD put in for q̈, the product with M⁻¹
    /// taken through the factor of M when it is sparse ([`derivatives`]).
    ///
    /// M⁻¹ and q̈ are built before the derivatives, so that the nodes of M⁻¹ come in the
    /// order [`Self::mass_matrix_inverse`] alone creates them in: the third output rounds
    /// exactly as that kernel does.
    pub fn forward_dynamics_derivatives(&mut self) -> (Matrix, Matrix, Matrix) {
        let inverse = self.mass_matrix_inverse();
        let qdd = self.forward_dynamics();
        let (dq, dv) = self.inverse_dynamics_derivatives();
        let [dq, dv] = self.at_accelerations([dq, dv], &qdd);
        let factor = self.mass_matrix_factor();
        let g = &mut self.model.graph;
        let dqdd_dq = derivatives::negated_inverse_times(g, &factor, &inverse, &dq);
        let dqdd_dv = derivatives::negated_inverse_times(g, &factor, &inverse, &dv);
        (dqdd_dq, dqdd_dv, inverse)
    }

    /// The matrices `m` (expressions of the acceleration symbols q̈) with the nodes `qdd` put
    /// in for q̈ ([`ExprGraph::substitute`]).
    fn at_accelerations(&mut self, [dq, dv]: [Matrix; 2], qdd: &[Id]) -> [Matrix; 2] {
        let values = acceleration_values(qdd);
        let g = &mut self.model.graph;
        let both = substitute_rows(g, &[dq, dv].concat(), &values);
        let (dq, dv) = both.split_at(both.len() / 2);
        [dq.to_vec(), dv.to_vec()]
    }

    /// (∂τ/∂q, ∂τ/∂q̇) as [`inverse_dynamics_derivatives`](Self::inverse_dynamics_derivatives)
    /// gives them, built in lanes ([`LanePartials`]): by forward sweeps (four directions a
    /// vector) or reverse sweeps (four torques a vector), whichever costs fewer operations.
    pub fn inverse_dynamics_derivative_lanes(&mut self) -> LanePartials {
        let tau = self.inverse_dynamics();
        let layout = self.layout();
        let g = &mut self.model.graph;
        let identity: Matrix = (0..tau.len())
            .map(|i| {
                (0..tau.len())
                    .map(|k| if i == k { g.one() } else { g.zero() })
                    .collect()
            })
            .collect();
        cheaper_lanes(
            g,
            |g| {
                let (groups, rows) = LanePartials::forward_rows(g, &tau, layout);
                LanePartials::from_rows(&groups, rows, layout.nv())
            },
            |g| LanePartials::reverse(g, &tau, &identity, layout),
        )
    }

    /// (∂q̈/∂q, ∂q̈/∂q̇) as [`forward_dynamics_derivatives`](Self::forward_dynamics_derivatives)
    /// gives them, built in lanes ([`LanePartials`]), and M⁻¹: by forward sweeps with −M⁻¹
    /// applied to each group's vectors, or by reverse sweeps seeded with the rows of −M⁻¹,
    /// whichever costs fewer operations.
    pub fn forward_dynamics_derivative_lanes(&mut self) -> (LanePartials, Matrix) {
        let inverse = self.mass_matrix_inverse();
        let qdd = self.forward_dynamics();
        let tau = self.inverse_dynamics();
        let layout = self.layout();
        let factor = self.mass_matrix_factor();
        let values = acceleration_values(&qdd);
        let g = &mut self.model.graph;
        let negated: Matrix = inverse
            .iter()
            .map(|row| row.iter().map(|&x| g.neg(x)).collect())
            .collect();
        let partials = cheaper_lanes(
            g,
            |g| {
                let (groups, rows) = LanePartials::forward_rows(g, &tau, layout);
                let rows = substitute_rows(g, &rows, &values);
                let rows = derivatives::negated_inverse_times(g, &factor, &inverse, &rows);
                LanePartials::from_rows(&groups, rows, layout.nv())
            },
            |g| {
                let mut partials = LanePartials::reverse(g, &tau, &negated, layout);
                partials.vectors = g.substitute(&partials.vectors, &values);
                partials
            },
        );
        (partials, inverse)
    }

    /// The frame of every link of the model as read (fixed links included), in link order.
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }

    /// Orientation (row-major) and origin in the world of the frames `selected` (indices into
    /// [`SymbolicDynamics::frames`]).
    pub fn frame_placements(&mut self, selected: &[usize]) -> Vec<(Mat3, Vec3)> {
        let zeros = self.zeros();
        let motion = self.motion(zeros.clone(), zeros);
        let g = &mut self.model.graph;
        let poses = energy::link_poses(g, &self.model.links, &motion);
        selected
            .iter()
            .map(|&f| {
                let frame = &self.frames[f];
                kinematics::frame_pose(g, frame.body.map(|b| poses[b]), frame)
            })
            .collect()
    }

    /// The geometric Jacobian of each selected frame: 6 × NV, rows [v; ω] of the frame origin
    /// in world axes (the `kinematics` module), the coefficients of v in the frame's velocity.
    pub fn frame_jacobians(&mut self, selected: &[usize]) -> Vec<Matrix> {
        let nv = self.layout().nv();
        let v: Vec<Id> = (0..nv)
            .map(|k| self.model.graph.symbol(Symbol::Velocity(k as u16)))
            .collect();
        let zeros = self.zeros();
        let motion = self.motion(v, zeros);
        let g = &mut self.model.graph;
        let poses = energy::link_poses(g, &self.model.links, &motion);
        let velocities = energy::link_velocities(g, &self.model.links, &motion);
        // One differentiator per velocity for every frame: the frames of a chain share the
        // velocities of the links before them, differentiated once.
        let mut differentiators: Vec<Differentiator> = (0..nv)
            .map(|k| Differentiator::new(Symbol::Velocity(k as u16)))
            .collect();
        selected
            .iter()
            .map(|&f| {
                let frame = &self.frames[f];
                let velocity = match frame.body {
                    Some(b) => kinematics::frame_velocity(g, &poses[b].0, velocities[b], frame),
                    None => [g.zero(); 6],
                };
                derivatives::symbol_jacobian(g, &velocity, &mut differentiators)
            })
            .collect()
    }

    /// J̇ q̇ of each selected frame: the classical acceleration [a; α] of the frame origin in
    /// world axes at q̈ = 0, without gravity.
    pub fn frame_jacobian_dot_qd(&mut self, selected: &[usize]) -> Vec<[Id; 6]> {
        let qd = self.velocity_symbols(Symbol::Velocity);
        let zeros = self.zeros();
        let gravity = self.model.graph.zero_vec();
        let motion = self.motion(qd, zeros);
        let recursion = newton_euler(&mut self.model, &motion, gravity);
        let g = &mut self.model.graph;
        let poses = energy::link_poses(g, &self.model.links, &motion);
        selected
            .iter()
            .map(|&f| {
                let frame = &self.frames[f];
                match frame.body {
                    Some(b) => {
                        let m = recursion.motion[b];
                        kinematics::frame_acceleration(
                            g,
                            &poses[b].0,
                            (m.omega, m.alpha, m.accel),
                            frame,
                        )
                    }
                    None => [g.zero(); 6],
                }
            })
            .collect()
    }

    /// The joint-torque regressor Y(q, q̇, q̈) of τ = Y π ([`regressor`]): NV rows, one column
    /// per standard parameter ([`Self::parameter_names`]).
    pub fn regressor(&mut self) -> Matrix {
        let qd = self.velocity_symbols(Symbol::Velocity);
        let qdd = self.velocity_symbols(Symbol::Acceleration);
        let motion = self.motion(qd, qdd);
        let gravity = self.model.gravity;
        regressor::regressor(&mut self.model, &motion, gravity, self.friction)
    }

    /// The names of the standard parameters, in the regressor's column order (`link.m`,
    /// `link.mcx`, ..., `link.fv`, `link.Ia`).
    pub fn parameter_names(&self) -> Vec<String> {
        regressor::regressor_columns(&self.model, self.friction)
            .iter()
            .map(|column| column.name(&self.model))
            .collect()
    }

    /// The base parameters of the regressor ([`base_parameters`]), from
    /// [`BASE_PARAMETER_SAMPLES`] seeded states, built in a copy of the graph.
    pub fn base_parameters(&self) -> BaseParameters {
        let mut scratch = self.clone();
        let y = scratch.regressor();
        BaseParameters::find(&scratch.model, &y, BASE_PARAMETER_SAMPLES)
    }

    /// The standard parameters π of the model, in the order of the regressor's columns, as
    /// expressions: per body m, m c and the inertia about the body origin; armatures.
    pub fn standard_parameters(&mut self) -> Vec<Id> {
        let columns = regressor::regressor_columns(&self.model, self.friction);
        let g = &mut self.model.graph;
        columns
            .iter()
            .map(|column| match *column {
                regressor::RegressorColumn::Body { link, parameter } => {
                    let body = match &self.bodies {
                        Some(bodies) => bodies[link],
                        None => BodyParameters::of_link(g, &self.model.links[link]),
                    };
                    match parameter {
                        0 => body.mass,
                        1..=3 => body.first_moment[parameter - 1],
                        p => {
                            let (a, b) = [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)][p - 4];
                            body.inertia[a][b]
                        }
                    }
                }
                regressor::RegressorColumn::Friction { link, parameter } => {
                    let friction = self.model.links[link].friction.expect("a friction column");
                    [friction.viscous, friction.coulomb, friction.offset][parameter]
                }
                regressor::RegressorColumn::Armature { link } => {
                    self.model.links[link].armature.unwrap_or_else(|| g.zero())
                }
            })
            .collect()
    }

    /// q̈ = FD(q, q̇, u) by the articulated-body algorithm (the `aba` module), linear in the number of
    /// links; `None` for a floating base or mimic couplings (use [`Self::forward_dynamics`]).
    pub fn forward_dynamics_articulated(&mut self) -> Option<Vec<Id>> {
        let qd = self.velocity_symbols(Symbol::Velocity);
        let u = self.driving_forces();
        let zeros = self.zeros();
        let motion = self.motion(qd, zeros);
        let gravity = self.model.gravity;
        let bodies = self.bodies.as_deref();
        aba::forward_dynamics(&mut self.model, &motion, &u, gravity, bodies)
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod floating_tests;

#[cfg(test)]
mod mimic_tests;

#[cfg(test)]
mod derivative_costs;
#[cfg(test)]
mod derivative_tests;

#[cfg(test)]
mod coriolis_tests;

/// The robot of `tests/fixtures/robots/{file}`, loaded with the default options: the unit
/// tests' fixtures.
#[cfg(test)]
fn fixture_robot(file: &str) -> RobotModel {
    let path = format!(
        "{}/tests/fixtures/robots/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    crate::read_robot(
        crate::Description::file(std::path::Path::new(&path)),
        &Default::default(),
    )
    .unwrap_or_else(|e| panic!("fixture {file}: {e}"))
}

/// The partials `forward` or `reverse` builds in lanes, whichever costs fewer operations
/// ([`cheaper_sweep`], each costed by [`crate::OpCount::cost`] over its vectors).
fn cheaper_lanes(
    g: &mut ExprGraph,
    forward: impl FnOnce(&mut ExprGraph) -> LanePartials,
    reverse: impl FnOnce(&mut ExprGraph) -> LanePartials,
) -> LanePartials {
    cheaper_sweep(g, costed_lanes(forward), costed_lanes(reverse)).1
}

/// `build` with the [`crate::OpCount::cost`] of the vectors it builds.
fn costed_lanes(
    build: impl FnOnce(&mut ExprGraph) -> LanePartials,
) -> impl FnOnce(&mut ExprGraph) -> (usize, LanePartials) {
    move |g| {
        let partials = build(g);
        (g.op_count(&partials.vectors).cost(), partials)
    }
}

/// What the forward and the reverse sweeps build (each builder returning its
/// [`crate::OpCount::cost`] and result), whichever costs less ([`derivatives::Sweep::cheaper`]:
/// forward on a tie), and which that was. Both are built in turn, the first taken out of the
/// graph while the second is tried ([`ExprGraph::split_off`]) and put back at the same ids if
/// it is kept, so the graph holds the kept one's nodes alone.
fn cheaper_sweep<T>(
    g: &mut ExprGraph,
    forward: impl FnOnce(&mut ExprGraph) -> (usize, T),
    reverse: impl FnOnce(&mut ExprGraph) -> (usize, T),
) -> (derivatives::Sweep, T) {
    let start = g.len();
    let (forward_cost, forward) = forward(g);
    let forward_nodes = g.split_off(start);
    let (reverse_cost, reverse) = reverse(g);
    match derivatives::Sweep::cheaper(forward_cost, reverse_cost) {
        derivatives::Sweep::Reverse => (derivatives::Sweep::Reverse, reverse),
        derivatives::Sweep::Forward => {
            g.split_off(start);
            g.restore(forward_nodes);
            (derivatives::Sweep::Forward, forward)
        }
    }
}
