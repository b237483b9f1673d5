//! The JSON written by `tools/peers/pinocchio_values.py`: per URDF, per base, Pinocchio's
//! joint order and its values at seeded states, in a layout that names joints rather than
//! Pinocchio's configuration entries (a continuous joint is one angle, not (cos, sin)).

use serde::Deserialize;

/// Everything the script wrote.
#[derive(Clone, Debug, Deserialize)]
pub struct PinocchioValues {
    /// Pinocchio's version.
    pub pinocchio: String,
    /// The seed of the states.
    pub seed: u64,
    /// States per robot and base.
    pub states: usize,
    /// One entry per URDF file, in path order.
    pub robots: Vec<RobotValues>,
}

/// One URDF file.
#[derive(Clone, Debug, Deserialize)]
pub struct RobotValues {
    /// Path relative to the robots directory.
    pub file: String,
    /// Bolted to the world, mimic semantics.
    pub fixed: BaseValues,
    /// On a free-flyer, mimic semantics.
    pub floating: BaseValues,
}

/// Pinocchio's model of a file on one base, and its values.
#[derive(Clone, Debug, Deserialize)]
pub struct BaseValues {
    /// Why Pinocchio could not load the file, if it could not.
    #[serde(default)]
    pub error: Option<String>,
    /// The joint variables by URDF name, in Pinocchio's velocity order (mimic followers have
    /// none).
    #[serde(default)]
    pub joints: Vec<String>,
    /// Size of the velocity (6 + joints on a floating base).
    #[serde(default)]
    pub nv: usize,
    /// `none` (no mimic joints), `pinocchio` (`mimic=True`), `projected` (`mimic=False` and
    /// the chain rule applied to Pinocchio's results, for files `mimic=True` refuses) or
    /// `free` (`mimic=False`, every follower a joint of its own, for files whose mimic joints
    /// follow no moving joint: compared with rne's reading with mimic joints free).
    #[serde(default)]
    pub mimic: Option<String>,
    /// The states.
    #[serde(default)]
    pub states: Vec<State>,
    /// Pinocchio's time for this file and base (loading and every state), ms.
    #[serde(default)]
    pub pinocchio_ms: f64,
}

/// One state and Pinocchio's results, velocity-sized vectors in the order of
/// [`BaseValues::joints`] after the free-flyer's six entries.
#[derive(Clone, Debug, Deserialize)]
pub struct State {
    /// `[x, y, z, qx, qy, qz, qw]` of a floating base.
    pub base: Option<[f64; 7]>,
    /// One value per joint.
    pub q: Vec<f64>,
    /// Velocity.
    pub v: Vec<f64>,
    /// Acceleration.
    pub a: Vec<f64>,
    /// Generalized forces of the forward-dynamics case.
    pub tau_fd: Vec<f64>,
    /// RNEA(q, v, a).
    pub tau: Vec<f64>,
    /// M(q), rows.
    #[serde(rename = "M")]
    pub mass_matrix: Vec<Vec<f64>>,
    /// g(q).
    pub g: Vec<f64>,
    /// C(q, v) v + g(q).
    pub bias: Vec<f64>,
    /// Forward dynamics at `tau_fd`; `None` when M is singular.
    pub qdd: Option<Vec<f64>>,
}
