//! The format-neutral input model both robot readers build, and the one step that turns it
//! into a [`RobotModel`].
//!
//! The TOML reader ([`crate::spec`]) and the URDF reader (`urdf`) each read their own
//! syntax into a `RobotInput`: the links in model order (parents first, joints numbered
//! depth-first), each built in a scratch [`ExprGraph`] with its frame convention mapped onto
//! `pre ∘ motion ∘ post` (`frames`) and its inertials in its body frame (`inertia`), plus
//! the names of the fields every number came from. `assemble` then validates the input at the
//! parameters' values (`validate`: errors and graded warnings), checks the mimic joints
//! (`mimic`), warns about moving joints that carry no mass, and copies the result into the
//! model's own graph (`transplant`), folding parameters or keeping them as symbols. Errors and
//! warnings name the link and field (or, for a URDF, the joint); each reader adds the file and
//! line, then `enforce` applies strict validation.
//!
//! [`read_robot`] reads a [`Description`] (a file, or text in a [`RobotFormat`]) with either
//! reader: the crate's one entry point for robot files.

mod format;
pub(crate) mod frames;
pub(crate) mod inertia;
pub(crate) mod mimic;
mod options;
mod read;
pub(crate) mod transplant;
pub(crate) mod validate;

pub use format::RobotFormat;
pub use options::LoadOptions;
pub use read::{read_robot, Description};
pub use validate::NEGLIGIBLE_INERTIA;

use self::frames::JointFrames;
use self::transplant::Transplant;
use self::validate::{LinkNumbers, Values};
use crate::expr::{ExprGraph, Mat3, Symbol, SymbolTable, Vec3};
use crate::model::{Base, Friction, JointVariable, Link, Mimic, Parameter};
use crate::spec::{SpecError, SpecWarning, SpecWarningKind};
use crate::RobotModel;

/// Joint variables (and parameters) a model may have: symbols are numbered with `u16`.
pub(crate) const MAX_SYMBOLS: usize = 1 << 16;

/// A robot as read from its file, before validation: expressions in a scratch graph.
#[derive(Debug)]
pub(crate) struct RobotInput {
    /// The robot's name.
    pub(crate) name: String,
    /// The scratch graph every expression below lives in.
    pub(crate) graph: ExprGraph,
    /// Named parameters and their values (`Symbol::Parameter(k)` is `parameters[k]`).
    pub(crate) parameters: Vec<Parameter>,
    /// Gravity in the base frame.
    pub(crate) gravity: Vec3,
    /// The links in model order.
    pub(crate) links: Vec<InputLink>,
    /// The joint variables in joint order.
    pub(crate) joints: Vec<JointVariable>,
    /// How the root is attached to the world.
    pub(crate) base: Base,
}

/// A link built in the scratch graph, and what the checks need to know about it.
#[derive(Clone, Debug)]
pub(crate) struct InputLink {
    /// The model link (expressions in the scratch graph).
    pub(crate) link: Link,
    /// The element that says how the link is attached, when it is not the link itself (a URDF
    /// `<joint>`): findings about the placement, axis, mimic and friction name it.
    pub(crate) joint_element: Option<String>,
    /// The convention's transforms, to check that they are finite.
    pub(crate) frames: JointFrames,
    /// The fields each part comes from, for messages.
    pub(crate) fields: Fields,
    /// The 3×3 array as written, which must be symmetric.
    pub(crate) declared_inertia: Option<Mat3>,
    /// The edge lengths of a box inertia, which must not be negative.
    pub(crate) box_edges: Option<Vec3>,
    /// Whether broken triangle inequalities of the principal moments are reported.
    pub(crate) triangle_inequality: bool,
}

/// The field each part of a link comes from, as messages name it.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Fields {
    pub(crate) rotation: &'static str,
    pub(crate) translation: &'static str,
    pub(crate) axis: &'static str,
    pub(crate) mass: &'static str,
    pub(crate) com: &'static str,
    pub(crate) inertia: &'static str,
    pub(crate) mimic: &'static str,
    pub(crate) mimic_multiplier: &'static str,
    pub(crate) mimic_offset: &'static str,
    pub(crate) viscous: &'static str,
    pub(crate) coulomb: &'static str,
    pub(crate) friction_offset: &'static str,
}

/// Whom a finding about a link belongs to.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Place {
    /// How the link is attached: its joint element if it has one, else the link.
    Joint,
    /// The link's own data (inertials).
    Link,
}

impl InputLink {
    /// `error` named after the joint element or the link, as `place` says.
    pub(crate) fn place(&self, place: Place, error: SpecError) -> SpecError {
        match (&self.joint_element, place) {
            (Some(joint), Place::Joint) => error.in_joint(joint),
            _ => error.in_link(&self.link.name),
        }
    }

    /// `warning` named after the joint element or the link, as `place` says.
    fn place_warning(&self, place: Place, warning: SpecWarning) -> SpecWarning {
        match (&self.joint_element, place) {
            (Some(joint), Place::Joint) => warning.in_joint(joint),
            _ => warning.in_link(&self.link.name),
        }
    }
}

/// Validates `input` and builds its model, with the warnings found (not yet located in the
/// file). [`LoadOptions::symbolic_parameters`] keeps every parameter as its own symbol instead
/// of folding it; [`LoadOptions::free_mimic`] drops mimic tags whose leader is missing.
pub(crate) fn assemble(
    mut input: RobotInput,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    let symbolic_parameters = options.symbolic_parameters;
    let values = Values::new(&input.graph, &input.parameters);
    validate::finite_vector(&values, &input.gravity, "gravity")?;
    let numbers = input
        .links
        .iter()
        .map(|link| validate::link(&values, link))
        .collect::<Result<Vec<LinkNumbers>, SpecError>>()?;
    let scale = numbers
        .iter()
        .fold(0.0_f64, |s, n| s.max(n.principal[2].abs()));
    let mut warnings = Vec::new();
    for (link, n) in input.links.iter().zip(&numbers) {
        let found = validate::inertia_tensor(n.principal, n.mass, link.triangle_inequality, scale)
            .map_err(|e| link.place(Place::Link, e.at_field(link.fields.inertia)))?;
        warnings.extend(
            found
                .into_iter()
                .map(|w| link.place_warning(Place::Link, w.at_field(link.fields.inertia))),
        );
    }
    if options.free_mimic {
        let dropped = mimic::drop_missing_leaders(&mut input.links, &input.joints);
        warnings.extend(
            dropped
                .into_iter()
                .map(|(l, w)| input.links[l].place_warning(Place::Joint, w)),
        );
    }
    mimic::check(&input.links, &input.joints)?;
    warnings.extend(massless_subtrees(&input.links, &numbers));

    let names: Vec<String> = input.joints.iter().map(|j| j.name.clone()).collect();
    let mut graph = ExprGraph::new(SymbolTable::with_joints(names));
    graph.set_exact_right_angles(options.exact_right_angles);
    if symbolic_parameters {
        for p in &input.parameters {
            graph.symbols_mut().push_parameter(p.name.clone());
        }
    }
    let parameters = &input.parameters;
    let symbol = |g: &mut ExprGraph, s: Symbol| match s {
        Symbol::Parameter(k) if !symbolic_parameters => {
            g.constant(parameters.get(k as usize).map_or(f64::NAN, |p| p.value))
        }
        s => g.symbol(s),
    };
    let mut copier = Transplant::new(&input.graph, graph, symbol);
    let gravity = copier.vector(input.gravity);
    let links = input
        .links
        .iter()
        .map(|l| copy_link(&mut copier, l.link.clone()))
        .collect();
    let graph = copier.finish();
    let mut model = RobotModel {
        name: input.name,
        graph,
        parameters: input.parameters,
        gravity,
        links,
        joints: input.joints,
        base: Base::Fixed,
        warnings,
    };
    // A floating base turns the root body into a free-flyer (RobotModel::set_base).
    model.set_base(input.base);
    Ok(model)
}

/// Strict validation: the model's first warning as an error, when `strict`.
pub(crate) fn enforce(model: RobotModel, strict: bool) -> Result<RobotModel, SpecError> {
    match model.warnings.first() {
        Some(warning) if strict => Err(warning.clone().into_error()),
        _ => Ok(model),
    }
}

/// A link with its expressions copied into the model's graph, in a fixed order (placement,
/// axis, inertials, mimic, friction, armature), so two readers that build the same expressions
/// get the same graph, node for node.
fn copy_link<F: FnMut(&mut ExprGraph, Symbol) -> crate::expr::Id>(
    copier: &mut Transplant<'_, F>,
    link: Link,
) -> Link {
    let rotation = copier.matrix(link.rotation);
    let translation = copier.vector(link.translation);
    let axis = copier.vector(link.axis);
    let mass = copier.scalar(link.mass);
    let com = copier.vector(link.com);
    let inertia = copier.matrix(link.inertia);
    let mimic = link.mimic.map(|m| Mimic {
        multiplier: copier.scalar(m.multiplier),
        offset: copier.scalar(m.offset),
        leader: m.leader,
    });
    let friction = link.friction.map(|f| Friction {
        viscous: copier.scalar(f.viscous),
        coulomb: copier.scalar(f.coulomb),
        offset: copier.scalar(f.offset),
    });
    let armature = link.armature.map(|a| copier.scalar(a));
    Link {
        rotation,
        translation,
        axis,
        mass,
        com,
        inertia,
        mimic,
        friction,
        armature,
        ..link
    }
}

/// A warning for each moving joint whose link and everything beyond it carry no mass or
/// inertia, the topmost of such joints only (the joints below it are part of its subtree).
fn massless_subtrees(links: &[InputLink], numbers: &[LinkNumbers]) -> Vec<SpecWarning> {
    let mut carries: Vec<bool> = numbers.iter().map(|n| n.carries).collect();
    for i in (0..links.len()).rev() {
        if let Some(p) = links[i].link.parent {
            if p < i {
                carries[p] |= carries[i];
            }
        }
    }
    let mut warnings = Vec::new();
    for (i, input) in links.iter().enumerate() {
        let link = &input.link;
        if link.joint.is_none() || carries[i] {
            continue;
        }
        let mut ancestor = link.parent;
        let mut inside = false;
        while let Some(a) = ancestor.filter(|&a| a < links.len()) {
            if links[a].link.joint.is_some() && !carries[a] {
                inside = true;
                break;
            }
            ancestor = links[a].link.parent;
        }
        if !inside {
            let warning = SpecWarning::new(
                SpecWarningKind::MasslessSubtree,
                format!(
                    "the joint moves no mass: link '{}' and every link beyond it have zero mass \
                     and inertia, so M(q) is singular and forward dynamics is undefined (the \
                     joint is kept for kinematics)",
                    link.name
                ),
            );
            warnings.push(input.place_warning(Place::Joint, warning));
        }
    }
    warnings
}
