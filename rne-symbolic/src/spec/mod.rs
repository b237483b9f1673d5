//! Robot specs: TOML files (docs/design.md §2.1) read into a [`RobotModel`].
//!
//! ```toml
//! name = "planar-elbow"
//! gravity = [0, "-g", 0]
//! [parameters]
//! g = 9.81
//! l1 = 0.3
//! [[link]]
//! name = "link1"
//! joint = "revolute"
//! rotation = "Rz(q1)"
//! position = ["l1", 0, 0]
//! mass = 15
//! com_from_prev = ["l1/2", 0, 0]
//! inertia = { box = ["l1", 0.08, 0.08] }
//! ```
//!
//! [`read_robot`](crate::read_robot) reads either format of docs/design.md §2, a TOML spec
//! (this module's reader, private behind it) or a URDF, as the file's extension or the caller
//! says ([`RobotFormat`]). Both readers build the shared input model of [`crate::input`], which validates it and assembles
//! the [`RobotModel`]; the errors ([`SpecError`]) and warnings ([`SpecWarning`]) of both are
//! defined here.
//!
//! # Reading
//!
//! 1. The TOML is read into a tree that remembers the line of every key and value
//!    (`document`); every table's keys are checked against the set it allows (`schema`).
//! 2. The links are put in model order: depth-first from the base, children in file order;
//!    joint variables are named (`q`, default `q<k>` counting movable joints in the file) and
//!    numbered in that order (`tree`).
//! 3. Parameters are defined in any order over each other, ordered by dependency and evaluated
//!    (`parameters`). Expression strings are parsed straight into an [`ExprGraph`]
//!    (`expression`), in which every parameter is its own symbol `Parameter(k)`.
//! 4. Each link's frame convention is mapped onto `pre ∘ motion(q) ∘ post`
//!    (`input::frames`), its placement is `parent.post ∘ pre`, its inertials are moved
//!    into the body frame, and its `mimic`, `friction` and `armature` are read (`assemble`):
//!    an `InputLink` of the shared input model.
//! 5. [`crate::input`] checks the result numerically (errors and warnings) and copies the
//!    model's expressions into the model's own graph, keeping parameters as symbols or folding
//!    them into constants ([`LoadOptions::symbolic_parameters`]). Because every structural
//!    check runs on the symbolic form, both modes accept the same specs. Warnings get the line
//!    of their field, and [`LoadOptions::strict`] turns the first into an error.
//!
//! # The format's details (docs/design.md §2.1 states them for users)
//!
//! - `gravity` defaults to `[0, 0, -9.81]` (z up, standard gravity rounded to 9.81 m/s²).
//! - The `origin`/`axis` convention follows URDF: `axis` defaults to `[1, 0, 0]` and is
//!   normalised; `origin.xyz` and `origin.rpy` default to zero. A zero axis is an error; so is an
//!   `axis` on a fixed joint, and a `q` on a fixed joint.
//! - `rotation` defaults to the identity and `position` to zero; a revolute joint's
//!   `rotation` must then still contain its variable, so omitting it is the error "joint
//!   variable missing from rotation" (docs/design.md §2.3).
//! - In `rotation`, `position`, `dh` and `mdh` the link's own joint variable may appear (in
//!   `dh`/`mdh` only in `theta` for a revolute joint or `d` for a prismatic one, as ±q + c; when
//!   it does not appear, q is added there). It may not appear in `origin`, `axis`, `mass`,
//!   `com` or `inertia`; another link's joint variable may appear nowhere.
//! - `com_from_prev` (r_{i−1,ci}) is accepted with the `rotation`/`position` convention on
//!   revolute and fixed joints, whose body origin is the origin of frame i−1; a prismatic joint
//!   moves that origin away from the link.
//! - `inertia` is required (a point mass writes zeros). A 3×3 array must be symmetric to a
//!   relative 1e-12; the model uses its upper triangle.
//! - Principal moments that break the triangle inequality are a warning;
//!   `triangle_inequality = false` silences it for a link, for published data that breaks it
//!   (PUMA 560 link 3); the spec should say why in a comment. A negative principal moment is a
//!   warning when negligible ([`crate::input::NEGLIGIBLE_INERTIA`]), else an error; a moving
//!   joint whose subtree has no mass is a warning.
//! - `base` is `"fixed"` (default) or `"floating"` ([`RobotModel::base`]).
//! - `mimic = { joint, multiplier, offset }`: `joint` is the leader's joint variable name (`q`
//!   of its link); `multiplier` (default 1) and `offset` (default 0) are expressions. The
//!   follower keeps its own `q` ([`Link::mimic`](crate::Link::mimic)). A missing leader, a
//!   loop of followers and a mimic on a fixed joint are errors; a leader of another joint type
//!   (a prismatic joint following a revolute one) is accepted, as URDF does.
//! - `friction = { viscous, coulomb, offset }` (each default 0) and `armature` are
//!   expressions; viscous, Coulomb and armature must be >= 0.
//! - Joint variable names must be identifiers, unique, and distinct from parameter names,
//!   also in their printed derivatives `D<q>`, `DD<q>` and force `tau_<q>`. Parameter and joint
//!   names may not be `pi`, `sqrt`, `sin`, `cos`, `Rx`, `Ry`, `Rz`; no link may be named `base`.
//! - An exponent must fold to a constant integer of magnitude at most 64, or 0.5; expressions
//!   nest at most 64 deep.

mod assemble;
mod diagnostic;
mod document;
mod error;
mod expression;
pub(crate) mod location;
mod parameters;
mod schema;
mod scope;
mod tree;
mod warning;

/// How a robot is read, re-exported where callers have always found it.
pub use crate::input::{LoadOptions, RobotFormat};
pub use diagnostic::Diagnostic;
pub use error::{SpecError, SpecErrorKind};
pub use warning::{SpecWarning, SpecWarningKind};

use self::document::Table;
use self::location::{Lines, Location};
use self::schema::{LinkSpec, RobotSpec};
use self::scope::Namespace;
use self::tree::Tree;
use crate::expr::{ExprGraph, SymbolTable, Vec3};
use crate::input::{self, InputLink, RobotInput};
use crate::model::Transform;
use crate::RobotModel;

/// Reads a spec from `text`; `origin` names the file in error and warning messages.
pub(crate) fn parse_str(
    text: &str,
    origin: &str,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    let root = document::parse(text).map_err(|e| e.locate(origin, text))?;
    let mut model = read(&root, options).map_err(|mut e| {
        with_position(e.location_mut(), &root, &LinkTables::new(&root));
        e.locate(origin, text)
    })?;
    let (tables, lines) = (LinkTables::new(&root), Lines::new(text));
    model.warnings = std::mem::take(&mut model.warnings)
        .into_iter()
        .map(|w| {
            let mut at = Location {
                link: w.link().map(str::to_owned),
                field: w.field().map(str::to_owned),
                ..Location::default()
            };
            with_position(&mut at, &root, &tables);
            w.at_span(at.span).locate_in(origin, &lines)
        })
        .collect();
    input::enforce(model, options.strict)
}

fn read(root: &Table, options: &LoadOptions) -> Result<RobotModel, SpecError> {
    let spec = schema::read(root)?;
    let parameter_names: Vec<&str> = spec
        .parameters
        .iter()
        .map(|p| p.name.name.as_str())
        .collect();
    let tree = tree::build(&spec.links, &parameter_names)?;
    let links: Vec<&LinkSpec<'_>> = tree
        .order
        .iter()
        .filter_map(|&s| spec.links.get(s))
        .collect();
    let link_names: Vec<&str> = links.iter().map(|l| l.name.name.as_str()).collect();
    let space = Namespace::new(&spec.parameters, &tree.joints, &link_names)?;

    let mut scratch = ExprGraph::new(SymbolTable::with_joints(tree.joint_names()));
    scratch.set_exact_right_angles(options.exact_right_angles);
    let parameters = parameters::define(&mut scratch, &spec.parameters, &space)?;
    let gravity = gravity(&mut scratch, &spec, &space)?;
    let built = assemble_links(&mut scratch, &tree, &links, &space)?;
    input::assemble(
        RobotInput {
            name: spec.name,
            graph: scratch,
            parameters,
            gravity,
            links: built,
            joints: tree.joints,
            base: spec.base,
        },
        options,
    )
}

/// Builds the links in model order, each placed by its parent's post-transform.
fn assemble_links(
    scratch: &mut ExprGraph,
    tree: &Tree,
    links: &[&LinkSpec<'_>],
    space: &Namespace,
) -> Result<Vec<InputLink>, SpecError> {
    let mut built: Vec<InputLink> = Vec::with_capacity(links.len());
    for (m, link) in links.iter().enumerate() {
        let parent = tree.parent.get(m).copied().flatten();
        let parent_post = match parent.and_then(|p| built.get(p)) {
            Some(p) => p.frames.post,
            None => Transform::identity(scratch),
        };
        let joint = tree.joint.get(m).copied().flatten();
        let assembled = assemble::link(scratch, link, parent, joint, &parent_post, space)
            .map_err(|e| e.in_link(&link.name.name))?;
        built.push(assembled);
    }
    Ok(built)
}

/// The gravity vector in the base frame (default `[0, 0, -9.81]`).
fn gravity(
    graph: &mut ExprGraph,
    spec: &RobotSpec<'_>,
    space: &Namespace,
) -> Result<Vec3, SpecError> {
    match &spec.gravity {
        Some(g) => space.scope(None, false).vector(graph, g),
        None => Ok(graph.const_vec([0.0, 0.0, -9.81])),
    }
}

/// Gives a finding without a position the position of its field (in its link, if any).
fn with_position(at: &mut Location, root: &Table, tables: &LinkTables<'_>) {
    let table = match &at.link {
        None => Some((root, None)),
        Some(name) => tables.get(name),
    };
    let span = table.and_then(|(table, link_span)| {
        at.field
            .as_deref()
            .and_then(|field| table.span_of(field))
            .or(link_span)
    });
    at.at_span(span);
}

/// The first `[[link]]` table of each name, and where it was written: found once for all the
/// findings of a file.
struct LinkTables<'r>(std::collections::HashMap<&'r str, (&'r Table, document::Span)>);

impl<'r> LinkTables<'r> {
    fn new(root: &'r Table) -> LinkTables<'r> {
        let mut tables = std::collections::HashMap::new();
        let links = root.get("link").and_then(|l| l.as_array("link").ok());
        for item in links.unwrap_or_default() {
            let Ok(table) = item.as_table("link") else {
                continue;
            };
            if let Some(name) = table.get("name").and_then(|n| n.as_str("name").ok()) {
                tables.entry(name).or_insert((table, item.span.clone()));
            }
        }
        LinkTables(tables)
    }

    fn get(&self, name: &str) -> Option<(&'r Table, document::Span)> {
        self.0.get(name).cloned()
    }
}
