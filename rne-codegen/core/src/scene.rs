//! The physical scene: the world the robot's generated functions describe — its gravity, the
//! joints that do not move, whether it is at rest, its base, its mimic couplings and its
//! friction. Everything here changes what the dynamics *are*; how they are written as code is
//! [`GenerationOptions`](crate::GenerationOptions).

use rne_symbolic::model::Base;
use rne_symbolic::RobotModel;

use crate::error::CodegenError;

/// The robot's world as the application sees it, so that only that is generated
/// (docs/design.md §3). Each field changes the equations of motion the kernels compute: a
/// scene at rest has no Coriolis terms, a locked joint no variable, a constrained mimic
/// follower no variable of its own, friction adds torques. Which functions are generated and
/// how their arithmetic is written are the [`GenerationOptions`](crate::GenerationOptions).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// Gravity overriding the spec's (`[0, 0, 0]` removes every gravity term).
    pub gravity: Option<[f64; 3]>,
    /// Joints locked at constant values: they become constants and leave the state.
    pub lock: Vec<(String, f64)>,
    /// A static scene (`at_rest: true`): every joint velocity is 0, so the Coriolis and
    /// centrifugal terms vanish. The functions keep their `qd` arguments and ignore them.
    pub at_rest: bool,
    /// The base overriding the spec's (`base: fixed | floating`); `None` keeps the spec's.
    pub base: Option<Base>,
    /// Whether mimic followers follow their leaders (the default, URDF semantics) or are
    /// joints of their own.
    pub mimic: MimicMode,
    /// Joint friction in the inverse and forward dynamics and the regressor
    /// (`friction: include`); `friction_torques` is available either way.
    pub friction: bool,
}

/// How mimic joints are generated (the macro's `mimic:` setting).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum MimicMode {
    /// URDF semantics: a follower has no variable; `q_f = multiplier · q_leader + offset`.
    #[default]
    Constrained,
    /// Every follower is an independent joint (Pinocchio's default when loading a URDF).
    Free,
}

impl Scene {
    /// The model as this scene sees it: the base set, mimic followers constrained (unless
    /// free), gravity overridden, joints locked. Something must move (a joint or a floating
    /// base), gravity must be finite, and each joint locked once at a finite position.
    pub fn apply(&self, model: &RobotModel) -> Result<RobotModel, CodegenError> {
        let mut model = model.clone();
        if let Some(base) = self.base {
            model.set_base(base);
        }
        if self.mimic == MimicMode::Constrained {
            model.constrain_mimic_joints()?;
        }
        model.check_moves()?;
        if let Some(gravity) = self.gravity {
            if !gravity.iter().all(|g| g.is_finite()) {
                return Err(CodegenError::Gravity(gravity));
            }
            model.set_gravity(gravity);
        }
        for (i, (joint, value)) in self.lock.iter().enumerate() {
            if self.lock[..i].iter().any(|(earlier, _)| earlier == joint) {
                return Err(CodegenError::LockedTwice(joint.clone()));
            }
            model.lock_joint(joint, *value)?;
        }
        Ok(model)
    }
}
