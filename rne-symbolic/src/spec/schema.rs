//! The tables of the spec format (docs/design.md §2.1) read from the TOML tree: every key checked
//! against the set its table allows, structural fields typed, frame convention and inertia
//! form recognised. Numbers stay unread ([`Number`]) until the expression stage.

use super::document::{join_path, Item, Span, Table, Value};
use super::error::{SpecError, SpecErrorKind};
use crate::model::{Base, JointKind};

const TOP_LEVEL_KEYS: &[&str] = &["name", "gravity", "base", "parameters", "link"];
const LINK_KEYS: &[&str] = &[
    "name",
    "parent",
    "joint",
    "q",
    "rotation",
    "position",
    "dh",
    "mdh",
    "origin",
    "axis",
    "mass",
    "com",
    "com_from_prev",
    "inertia",
    "triangle_inequality",
    "mimic",
    "friction",
    "armature",
];
const DH_KEYS: &[&str] = &["a", "alpha", "d", "theta"];
const ORIGIN_KEYS: &[&str] = &["xyz", "rpy"];
const INERTIA_KEYS: &[&str] = &["xx", "yy", "zz", "xy", "xz", "yz"];
const BOX_KEYS: &[&str] = &["box"];
const MIMIC_KEYS: &[&str] = &["joint", "multiplier", "offset"];
const FRICTION_KEYS: &[&str] = &["viscous", "coulomb", "offset"];

/// A number or an expression string, with the field path it was found at.
#[derive(Clone, Debug)]
pub(crate) struct Number<'a> {
    pub(crate) field: String,
    pub(crate) item: &'a Item,
}

/// Three numbers.
pub(crate) type Vector<'a> = [Number<'a>; 3];

/// A string field and where it was written.
#[derive(Clone, Debug)]
pub(crate) struct Named {
    pub(crate) name: String,
    pub(crate) span: Span,
}

/// A whole spec, checked for unknown keys and typed.
#[derive(Debug)]
pub(crate) struct RobotSpec<'a> {
    pub(crate) name: String,
    pub(crate) gravity: Option<Vector<'a>>,
    pub(crate) base: Base,
    pub(crate) parameters: Vec<ParameterSpec<'a>>,
    pub(crate) links: Vec<LinkSpec<'a>>,
}

/// One entry of `[parameters]`.
#[derive(Debug)]
pub(crate) struct ParameterSpec<'a> {
    pub(crate) name: Named,
    pub(crate) value: Number<'a>,
}

/// One `[[link]]`.
#[derive(Debug)]
pub(crate) struct LinkSpec<'a> {
    pub(crate) name: Named,
    pub(crate) parent: Option<Named>,
    pub(crate) kind: JointKind,
    pub(crate) q: Option<Named>,
    pub(crate) frame: FrameSpec<'a>,
    pub(crate) mass: Number<'a>,
    pub(crate) com: ComSpec<'a>,
    pub(crate) inertia: InertiaSpec<'a>,
    pub(crate) triangle_inequality: bool,
    pub(crate) mimic: Option<MimicSpec<'a>>,
    pub(crate) friction: Option<FrictionSpec<'a>>,
    pub(crate) armature: Option<Number<'a>>,
}

/// `mimic = { joint, multiplier, offset }`: the leader's joint variable, the factor and offset
/// (defaults 1 and 0).
#[derive(Debug)]
pub(crate) struct MimicSpec<'a> {
    pub(crate) joint: Named,
    pub(crate) multiplier: Option<Number<'a>>,
    pub(crate) offset: Option<Number<'a>>,
}

/// `friction = { viscous, coulomb, offset }`, each defaulting to 0.
#[derive(Debug)]
pub(crate) struct FrictionSpec<'a> {
    pub(crate) viscous: Option<Number<'a>>,
    pub(crate) coulomb: Option<Number<'a>>,
    pub(crate) offset: Option<Number<'a>>,
}

/// The frame convention of a link (docs/design.md §2.1 (a)–(d)); omitted entries are `None`.
#[derive(Debug)]
pub(crate) enum FrameSpec<'a> {
    /// (a) the thesis's `rotation` R_i^{i−1}(q) and `position` r_{i−1,i} in frame i.
    Thesis {
        rotation: Option<Named>,
        position: Option<Vector<'a>>,
    },
    /// (b) standard Denavit–Hartenberg.
    Dh(DhSpec<'a>),
    /// (c) modified Denavit–Hartenberg (Craig).
    Mdh(DhSpec<'a>),
    /// (d) URDF `origin` and `axis`.
    Urdf {
        xyz: Option<Vector<'a>>,
        rpy: Option<Vector<'a>>,
        axis: Option<Vector<'a>>,
    },
}

/// The entries of a `dh` or `mdh` table.
#[derive(Debug)]
pub(crate) struct DhSpec<'a> {
    pub(crate) a: Option<Number<'a>>,
    pub(crate) alpha: Option<Number<'a>>,
    pub(crate) d: Option<Number<'a>>,
    pub(crate) theta: Option<Number<'a>>,
}

/// Where the centre of mass is given.
#[derive(Debug)]
pub(crate) enum ComSpec<'a> {
    /// Not given: the origin of frame i.
    Origin,
    /// `com`: relative to the origin of frame i, in frame i (r_{i,ci}).
    Frame(Vector<'a>),
    /// `com_from_prev`: relative to the body origin, the origin of frame i−1 (r_{i−1,ci}).
    FromPrevious(Vector<'a>),
}

/// The three ways to write an inertia tensor about the COM, in the axes of frame i.
#[derive(Debug)]
pub(crate) enum InertiaSpec<'a> {
    /// `{ xx, yy, zz, xy, xz, yz }`, products of inertia optional.
    Components {
        diagonal: Vector<'a>,
        products: [Option<Number<'a>>; 3],
    },
    /// A 3×3 array, which must be symmetric.
    Matrix([Vector<'a>; 3]),
    /// `{ box = [lx, ly, lz] }`: a uniform box of these edge lengths centred at the COM.
    Box(Vector<'a>),
}

/// Reads the top level of a spec.
pub(crate) fn read(root: &Table) -> Result<RobotSpec<'_>, SpecError> {
    root.check_keys(TOP_LEVEL_KEYS, "")?;
    let name = root.required("name", "")?.as_str("name")?.to_owned();
    let gravity = root
        .get("gravity")
        .map(|g| vector(g, "gravity"))
        .transpose()?;
    let base = match root.get("base") {
        None => Base::Fixed,
        Some(item) => match item.as_str("base")? {
            "fixed" => Base::Fixed,
            "floating" => Base::Floating,
            other => {
                return Err(format_error(format!(
                    "unknown base '{other}' (expected fixed or floating)"
                ))
                .at_field("base")
                .at_span(item.span.clone()))
            }
        },
    };
    let parameters = match root.get("parameters") {
        None => Vec::new(),
        Some(item) => item
            .as_table("parameters")?
            .entries()
            .iter()
            .map(|entry| ParameterSpec {
                name: Named {
                    name: entry.key.clone(),
                    span: entry.key_span.clone(),
                },
                value: Number {
                    field: join_path("parameters", &entry.key),
                    item: &entry.item,
                },
            })
            .collect(),
    };
    let links = match root.get("link") {
        None => Vec::new(),
        Some(item) => match &item.value {
            Value::Array(links) => links.iter().map(link).collect::<Result<_, _>>()?,
            _ => return Err(item.type_error("an array of tables [[link]]", "link")),
        },
    };
    Ok(RobotSpec {
        name,
        gravity,
        base,
        parameters,
        links,
    })
}

fn link(item: &Item) -> Result<LinkSpec<'_>, SpecError> {
    let table = item.as_table("link")?;
    let name =
        named(table.required("name", "")?, "name").map_err(|e| e.at_span(item.span.clone()))?;
    read_link(table).map_err(|e| {
        // Resolved here, in this very table: a later link may share the name.
        let span = e
            .field()
            .and_then(|f| table.span_of(f))
            .or(item.span.clone());
        e.in_link(&name.name).at_span(span)
    })
}

fn read_link(table: &Table) -> Result<LinkSpec<'_>, SpecError> {
    table.check_keys(LINK_KEYS, "")?;
    let name = named(table.required("name", "")?, "name")?;
    if name.name.is_empty() {
        return Err(format_error("a link name must not be empty").at_field("name"));
    }
    let parent = table
        .get("parent")
        .map(|p| named(p, "parent"))
        .transpose()?;
    let joint = named(table.required("joint", "")?, "joint")?;
    let kind = match joint.name.as_str() {
        "revolute" => JointKind::Revolute,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        other => {
            return Err(format_error(format!(
                "unknown joint kind '{other}' (expected revolute, prismatic or fixed)"
            ))
            .at_field("joint"))
        }
    };
    let q = table.get("q").map(|q| named(q, "q")).transpose()?;
    if kind == JointKind::Fixed && q.is_some() {
        return Err(format_error("a fixed joint has no joint variable").at_field("q"));
    }
    let frame = frame(table, kind)?;
    let mass = Number {
        field: "mass".to_owned(),
        item: table.required("mass", "")?,
    };
    let com = com(table, &frame, kind)?;
    let inertia = inertia(table.required("inertia", "")?)?;
    let triangle_inequality = table
        .get("triangle_inequality")
        .map(|t| t.as_bool("triangle_inequality"))
        .transpose()?
        .unwrap_or(true);
    let mimic = table.get("mimic").map(mimic).transpose()?;
    let friction = table.get("friction").map(friction).transpose()?;
    let armature = table.get("armature").map(|item| Number {
        field: "armature".to_owned(),
        item,
    });
    Ok(LinkSpec {
        name,
        parent,
        kind,
        q,
        frame,
        mass,
        com,
        inertia,
        triangle_inequality,
        mimic,
        friction,
        armature,
    })
}

fn mimic(item: &Item) -> Result<MimicSpec<'_>, SpecError> {
    let table = item.as_table("mimic")?;
    table.check_keys(MIMIC_KEYS, "mimic")?;
    let number = |k: &str| {
        table.get(k).map(|item| Number {
            field: join_path("mimic", k),
            item,
        })
    };
    Ok(MimicSpec {
        joint: named(table.required("joint", "mimic")?, "mimic.joint")?,
        multiplier: number("multiplier"),
        offset: number("offset"),
    })
}

fn friction(item: &Item) -> Result<FrictionSpec<'_>, SpecError> {
    let table = item.as_table("friction")?;
    table.check_keys(FRICTION_KEYS, "friction")?;
    let number = |k: &str| {
        table.get(k).map(|item| Number {
            field: join_path("friction", k),
            item,
        })
    };
    Ok(FrictionSpec {
        viscous: number("viscous"),
        coulomb: number("coulomb"),
        offset: number("offset"),
    })
}

/// The frame conventions, their names in messages and the keys that select them.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Convention {
    Thesis,
    Dh,
    Mdh,
    Urdf,
}

const CONVENTIONS: [(Convention, &str, &[&str]); 4] = [
    (
        Convention::Thesis,
        "rotation/position",
        &["rotation", "position"],
    ),
    (Convention::Dh, "dh", &["dh"]),
    (Convention::Mdh, "mdh", &["mdh"]),
    (Convention::Urdf, "origin/axis", &["origin", "axis"]),
];

/// Recognises exactly one frame convention.
fn frame(table: &Table, kind: JointKind) -> Result<FrameSpec<'_>, SpecError> {
    let present: Vec<(Convention, &str)> = CONVENTIONS
        .iter()
        .filter(|(_, _, keys)| keys.iter().any(|k| table.contains(k)))
        .map(|&(convention, name, _)| (convention, name))
        .collect();
    let convention = match present.as_slice() {
        [] => {
            return Err(format_error(
                "no frame convention: give one of rotation/position, dh, mdh or origin/axis",
            ))
        }
        [(convention, _)] => *convention,
        [(_, first), (_, second), ..] => {
            return Err(format_error(format!(
                "two frame conventions, {first} and {second}: give exactly one of rotation/position, dh, \
                 mdh or origin/axis"
            )))
        }
    };
    match convention {
        Convention::Thesis => Ok(FrameSpec::Thesis {
            rotation: table
                .get("rotation")
                .map(|r| named(r, "rotation"))
                .transpose()?,
            position: table
                .get("position")
                .map(|p| vector(p, "position"))
                .transpose()?,
        }),
        Convention::Dh => dh(table, "dh").map(FrameSpec::Dh),
        Convention::Mdh => dh(table, "mdh").map(FrameSpec::Mdh),
        Convention::Urdf => {
            let (xyz, rpy) = match table.get("origin") {
                None => (None, None),
                Some(origin) => {
                    let origin = origin.as_table("origin")?;
                    origin.check_keys(ORIGIN_KEYS, "origin")?;
                    let xyz = origin
                        .get("xyz")
                        .map(|v| vector(v, "origin.xyz"))
                        .transpose()?;
                    let rpy = origin
                        .get("rpy")
                        .map(|v| vector(v, "origin.rpy"))
                        .transpose()?;
                    (xyz, rpy)
                }
            };
            let axis = table.get("axis").map(|a| vector(a, "axis")).transpose()?;
            if kind == JointKind::Fixed && axis.is_some() {
                return Err(format_error("a fixed joint has no axis").at_field("axis"));
            }
            Ok(FrameSpec::Urdf { xyz, rpy, axis })
        }
    }
}

fn dh<'a>(table: &'a Table, key: &str) -> Result<DhSpec<'a>, SpecError> {
    let entries = table.get(key).map(|t| t.as_table(key)).transpose()?;
    let Some(entries) = entries else {
        return Ok(DhSpec {
            a: None,
            alpha: None,
            d: None,
            theta: None,
        });
    };
    entries.check_keys(DH_KEYS, key)?;
    let number = |k: &str| {
        entries.get(k).map(|item| Number {
            field: join_path(key, k),
            item,
        })
    };
    Ok(DhSpec {
        a: number("a"),
        alpha: number("alpha"),
        d: number("d"),
        theta: number("theta"),
    })
}

fn com<'a>(
    table: &'a Table,
    frame: &FrameSpec<'a>,
    kind: JointKind,
) -> Result<ComSpec<'a>, SpecError> {
    match (table.get("com"), table.get("com_from_prev")) {
        (None, None) => Ok(ComSpec::Origin),
        (Some(com), None) => vector(com, "com").map(ComSpec::Frame),
        (Some(_), Some(_)) => {
            Err(format_error("give either com or com_from_prev, not both")
                .at_field("com_from_prev"))
        }
        (None, Some(from_previous)) => {
            if !matches!(frame, FrameSpec::Thesis { .. }) {
                return Err(format_error(
                    "com_from_prev belongs to the rotation/position convention; use com",
                )
                .at_field("com_from_prev"));
            }
            if kind == JointKind::Prismatic {
                return Err(format_error(
                    "com_from_prev is measured from the origin of frame i-1, which a prismatic joint moves \
                     away from the link; use com",
                )
                .at_field("com_from_prev"));
            }
            vector(from_previous, "com_from_prev").map(ComSpec::FromPrevious)
        }
    }
}

fn inertia(item: &Item) -> Result<InertiaSpec<'_>, SpecError> {
    match &item.value {
        Value::Array(_) => {
            let [r0, r1, r2] = item.as_fixed_array::<3>("inertia")?;
            Ok(InertiaSpec::Matrix([
                vector(r0, "inertia[0]")?,
                vector(r1, "inertia[1]")?,
                vector(r2, "inertia[2]")?,
            ]))
        }
        Value::Table(table) if table.contains("box") => {
            table.check_keys(BOX_KEYS, "inertia")?;
            vector(table.required("box", "inertia")?, "inertia.box").map(InertiaSpec::Box)
        }
        Value::Table(table) => {
            table.check_keys(INERTIA_KEYS, "inertia")?;
            let required = |k: &str| -> Result<Number<'_>, SpecError> {
                Ok(Number {
                    field: join_path("inertia", k),
                    item: table.required(k, "inertia")?,
                })
            };
            let optional = |k: &str| {
                table.get(k).map(|item| Number {
                    field: join_path("inertia", k),
                    item,
                })
            };
            Ok(InertiaSpec::Components {
                diagonal: [required("xx")?, required("yy")?, required("zz")?],
                products: [optional("xy"), optional("xz"), optional("yz")],
            })
        }
        _ => Err(item.type_error(
            "a table { xx, yy, zz, ... }, { box = [..] } or a 3x3 array",
            "inertia",
        )),
    }
}

/// An array of three numbers at `field`.
fn vector<'a>(item: &'a Item, field: &str) -> Result<Vector<'a>, SpecError> {
    let mut i = 0;
    Ok(item.as_fixed_array::<3>(field)?.map(|item| {
        i += 1;
        Number {
            field: format!("{field}[{}]", i - 1),
            item,
        }
    }))
}

fn named(item: &Item, field: &str) -> Result<Named, SpecError> {
    Ok(Named {
        name: item.as_str(field)?.to_owned(),
        span: item.span.clone(),
    })
}

fn format_error(message: impl Into<String>) -> SpecError {
    SpecError::new(SpecErrorKind::Format, message)
}
