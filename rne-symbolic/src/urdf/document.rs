//! The URDF XML read with quick-xml into [`UrdfRobot`]: only the elements and attributes the
//! dynamics needs are looked at. Any other element (with everything inside it), any other
//! attribute, comments, processing instructions, DOCTYPE and text are skipped unread, so they
//! cannot make a load fail; the first of repeated elements counts, as in urdfdom.
//!
//! Read: `<robot name>`; `<link name>` and its `<inertial>` with `<origin xyz rpy>`,
//! `<mass value>` and `<inertia ixx ixy ixz iyy iyz izz>`; `<joint name type>` with `<origin
//! xyz rpy>`, `<parent link>`, `<child link>`, `<axis xyz>`, `<mimic joint multiplier offset>`
//! and `<dynamics damping friction>`. Required: a link's and a joint's `name`, a joint's `type`,
//! `<parent>` and `<child>`, and inside an `<inertial>` its `<mass>` and `<inertia>` with every
//! attribute. Numbers must parse and be finite.

use std::ops::Range;

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use super::elements::{Dynamics, Inertial, JointType, UrdfJoint, UrdfLink, UrdfMimic, UrdfRobot};
use super::MJCF_UNSUPPORTED;
use crate::input::validate::finite;
use crate::spec::{SpecError, SpecErrorKind};

/// The deepest element nesting read. URDF elements nest five deep at most (`robot`, `link`,
/// `visual`, `geometry`, `mesh`); the limit keeps absurd files from costing memory.
const MAX_NESTING: usize = 64;

/// What an open element is, for the elements inside it.
#[derive(Debug)]
enum Open {
    Robot,
    Link(LinkDraft),
    Inertial(InertialDraft),
    Joint(JointDraft),
    /// An element the dynamics does not read: everything inside it is skipped.
    Skipped,
}

#[derive(Debug)]
struct LinkDraft {
    name: String,
    span: Range<usize>,
    inertial: Option<Inertial>,
}

#[derive(Debug, Default)]
struct InertialDraft {
    origin: Option<([f64; 3], [f64; 3])>,
    mass: Option<f64>,
    inertia: Option<[[f64; 3]; 3]>,
}

#[derive(Debug)]
struct JointDraft {
    name: String,
    span: Range<usize>,
    joint_type: JointType,
    origin: Option<([f64; 3], [f64; 3])>,
    parent: Option<String>,
    child: Option<String>,
    axis: Option<[f64; 3]>,
    mimic: Option<UrdfMimic>,
    dynamics: Option<Dynamics>,
}

/// Reads `text`. Errors carry the byte range of the element at fault (and its joint or link).
pub(crate) fn read(text: &str) -> Result<UrdfRobot, SpecError> {
    let mut reader = Reader::from_str(text);
    let mut robot = UrdfRobot::default();
    let mut open: Vec<(Open, Range<usize>)> = Vec::new();
    let mut seen_robot = false;
    loop {
        let start = position(reader.buffer_position());
        let event = reader.read_event().map_err(|e| {
            let at = position(reader.error_position());
            urdf_error(format!("cannot read the URDF: malformed XML: {e}")).at_span(Some(at..at))
        })?;
        let (element, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                if let Some((element, _)) = open.pop() {
                    close(&mut robot, open.last_mut().map(|(o, _)| o), element)?;
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let span = start..position(reader.buffer_position());
        if open.len() >= MAX_NESTING {
            return Err(urdf_error(format!(
                "cannot read the URDF: elements nest more than {MAX_NESTING} deep"
            ))
            .at_span(Some(span)));
        }
        let opened = match open.last_mut() {
            None if seen_robot => Open::Skipped,
            None => {
                if element.name().as_ref() == b"mujoco" {
                    return Err(urdf_error(MJCF_UNSUPPORTED.to_owned()).at_span(Some(span)));
                }
                if element.name().as_ref() != b"robot" {
                    return Err(urdf_error(format!(
                        "cannot read the URDF: the root element is <{}>, not <robot>",
                        String::from_utf8_lossy(element.name().as_ref())
                    ))
                    .at_span(Some(span)));
                }
                seen_robot = true;
                robot.name = attribute(&element, "name")?;
                Open::Robot
            }
            Some((parent, _)) => {
                child(parent, &element, &span).map_err(|e| owner(&open, e, &span))?
            }
        };
        if empty {
            close(&mut robot, open.last_mut().map(|(o, _)| o), opened)?;
        } else {
            open.push((opened, span));
        }
    }
    if let Some((_, span)) = open.last() {
        return Err(urdf_error(
            "cannot read the URDF: the file ends inside an element opened here",
        )
        .at_span(Some(span.clone())));
    }
    if !seen_robot {
        return Err(urdf_error(
            "cannot read the URDF: there is no <robot> element",
        ));
    }
    Ok(robot)
}

/// `error` about an element at `span` inside the open elements `open`, named after the innermost
/// open `<link>` or `<joint>` and placed at its opening tag (or at `span` outside them).
fn owner(open: &[(Open, Range<usize>)], error: SpecError, span: &Range<usize>) -> SpecError {
    for (element, _) in open.iter().rev() {
        match element {
            Open::Link(link) => return error.in_link(&link.name).at_span(Some(link.span.clone())),
            Open::Joint(joint) => {
                return error
                    .in_joint(&joint.name)
                    .at_span(Some(joint.span.clone()))
            }
            _ => {}
        }
    }
    error.at_span(Some(span.clone()))
}

/// What the element `element`, inside `parent`, is.
fn child(
    parent: &mut Open,
    element: &BytesStart<'_>,
    span: &Range<usize>,
) -> Result<Open, SpecError> {
    let name = element.name();
    Ok(match (parent, name.as_ref()) {
        (Open::Robot, b"link") => {
            let name =
                required(element, "name", "name").map_err(|e| e.at_span(Some(span.clone())))?;
            Open::Link(LinkDraft {
                name,
                span: span.clone(),
                inertial: None,
            })
        }
        (Open::Robot, b"joint") => Open::Joint(joint_draft(element, span)?),
        (Open::Link(link), b"inertial") if link.inertial.is_none() => {
            Open::Inertial(InertialDraft::default())
        }
        (Open::Inertial(inertial), tag) => {
            inertial_child(inertial, tag, element)?;
            Open::Skipped
        }
        (Open::Joint(joint), tag) => {
            let name = joint.name.clone();
            joint_child(joint, tag, element).map_err(|e| e.in_joint(&name))?;
            Open::Skipped
        }
        _ => Open::Skipped,
    })
}

/// A `<joint>` as opened at `span`: its name and type, nothing inside it read yet.
fn joint_draft(element: &BytesStart<'_>, span: &Range<usize>) -> Result<JointDraft, SpecError> {
    let name = required(element, "name", "name").map_err(|e| e.at_span(Some(span.clone())))?;
    let in_joint = |e: SpecError| e.in_joint(&name).at_span(Some(span.clone()));
    let type_name = required(element, "type", "type").map_err(in_joint)?;
    let joint_type = JointType::from_name(&type_name).ok_or_else(|| {
        in_joint(
            urdf_error(format!(
                "unknown joint type '{type_name}' (expected revolute, continuous, \
                 prismatic, fixed, floating, planar or spherical)"
            ))
            .at_field("type"),
        )
    })?;
    Ok(JointDraft {
        name,
        span: span.clone(),
        joint_type,
        origin: None,
        parent: None,
        child: None,
        axis: None,
        mimic: None,
        dynamics: None,
    })
}

/// Reads the element `tag` inside an `<inertial>` into it (the first of each counts).
fn inertial_child(
    inertial: &mut InertialDraft,
    tag: &[u8],
    element: &BytesStart<'_>,
) -> Result<(), SpecError> {
    match tag {
        b"origin" if inertial.origin.is_none() => {
            inertial.origin = Some(origin(element, "inertial.origin")?);
        }
        b"mass" if inertial.mass.is_none() => {
            let value = required(element, "value", "inertial.mass")?;
            inertial.mass = Some(number(&value, "inertial.mass")?);
        }
        b"inertia" if inertial.inertia.is_none() => {
            let mut values = [0.0; 6];
            for (value, key) in values
                .iter_mut()
                .zip(["ixx", "ixy", "ixz", "iyy", "iyz", "izz"])
            {
                let field = format!("inertial.inertia.{key}");
                *value = number(&required(element, key, &field)?, &field)?;
            }
            let [xx, xy, xz, yy, yz, zz] = values;
            inertial.inertia = Some([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]);
        }
        _ => {}
    }
    Ok(())
}

/// Reads the element `tag` inside a `<joint>` into it (the first of each counts).
fn joint_child(
    joint: &mut JointDraft,
    tag: &[u8],
    element: &BytesStart<'_>,
) -> Result<(), SpecError> {
    match tag {
        b"origin" if joint.origin.is_none() => {
            joint.origin = Some(origin(element, "origin")?);
        }
        b"parent" if joint.parent.is_none() => {
            joint.parent = Some(required(element, "link", "parent")?);
        }
        b"child" if joint.child.is_none() => {
            joint.child = Some(required(element, "link", "child")?);
        }
        b"axis" if joint.axis.is_none() => {
            let xyz = attribute(element, "xyz")?;
            joint.axis = Some(match xyz {
                Some(xyz) => vector(&xyz, "axis")?,
                None => [1.0, 0.0, 0.0],
            });
        }
        b"mimic" if joint.mimic.is_none() => {
            joint.mimic = Some(mimic(element)?);
        }
        b"dynamics" if joint.dynamics.is_none() => {
            let coefficient = |key: &str| -> Result<f64, SpecError> {
                let field = format!("dynamics.{key}");
                match attribute(element, key)? {
                    Some(value) => number(&value, &field),
                    None => Ok(0.0),
                }
            };
            joint.dynamics = Some(Dynamics {
                damping: coefficient("damping")?,
                friction: coefficient("friction")?,
            });
        }
        _ => {}
    }
    Ok(())
}

/// Files a closed element into its parent (or the robot).
fn close(robot: &mut UrdfRobot, parent: Option<&mut Open>, element: Open) -> Result<(), SpecError> {
    match element {
        Open::Link(link) => robot.links.push(UrdfLink {
            name: link.name,
            span: link.span,
            inertial: link.inertial,
        }),
        Open::Joint(joint) => {
            let error = |field: &str| {
                urdf_error(format!("the joint has no <{field} link=\"..\"/>"))
                    .at_field(field)
                    .in_joint(&joint.name)
                    .at_span(Some(joint.span.clone()))
            };
            let parent = joint.parent.clone().ok_or_else(|| error("parent"))?;
            let child = joint.child.clone().ok_or_else(|| error("child"))?;
            let (xyz, rpy) = joint.origin.unwrap_or_default();
            robot.joints.push(UrdfJoint {
                name: joint.name,
                span: joint.span,
                joint_type: joint.joint_type,
                parent,
                child,
                xyz,
                rpy,
                axis: joint.axis.unwrap_or([1.0, 0.0, 0.0]),
                mimic: joint.mimic,
                dynamics: joint.dynamics,
            });
        }
        Open::Inertial(inertial) => {
            if let Some(Open::Link(link)) = parent {
                let in_link = |e: SpecError| e.in_link(&link.name).at_span(Some(link.span.clone()));
                let missing = |what: &str, field: &str| {
                    in_link(urdf_error(format!("the <inertial> has no <{what}>")).at_field(field))
                };
                let (xyz, rpy) = inertial.origin.unwrap_or_default();
                link.inertial = Some(Inertial {
                    xyz,
                    rpy,
                    mass: inertial
                        .mass
                        .ok_or_else(|| missing("mass value=\"..\"/", "inertial.mass"))?,
                    inertia: inertial.inertia.ok_or_else(|| {
                        missing("inertia ixx=\"..\" .. izz=\"..\"/", "inertial.inertia")
                    })?,
                });
            }
        }
        Open::Robot | Open::Skipped => {}
    }
    Ok(())
}

/// `<origin xyz rpy>`, each defaulting to zero; `field` names the element.
fn origin(element: &BytesStart<'_>, field: &str) -> Result<([f64; 3], [f64; 3]), SpecError> {
    let read = |key: &str| -> Result<[f64; 3], SpecError> {
        match attribute(element, key)? {
            Some(value) => vector(&value, &format!("{field}.{key}")),
            None => Ok([0.0; 3]),
        }
    };
    Ok((read("xyz")?, read("rpy")?))
}

/// `<mimic joint multiplier offset>`.
fn mimic(element: &BytesStart<'_>) -> Result<UrdfMimic, SpecError> {
    let optional = |key: &str, default: f64| -> Result<f64, SpecError> {
        match attribute(element, key)? {
            Some(value) => number(&value, &format!("mimic.{key}")),
            None => Ok(default),
        }
    };
    Ok(UrdfMimic {
        joint: required(element, "joint", "mimic.joint")?,
        multiplier: optional("multiplier", 1.0)?,
        offset: optional("offset", 0.0)?,
    })
}

/// The value of the attribute `key` of `element`, unescaped; later duplicates are ignored.
fn attribute(element: &BytesStart<'_>, key: &str) -> Result<Option<String>, SpecError> {
    let mut attributes = element.attributes();
    attributes.with_checks(false);
    for attribute in attributes {
        let attribute = attribute
            .map_err(|e| urdf_error(format!("cannot read the URDF: malformed attribute: {e}")))?;
        if attribute.key.as_ref() == key.as_bytes() {
            let value = attribute.unescape_value().map_err(|e| {
                urdf_error(format!("cannot read the attribute '{key}': {e}")).at_field(key)
            })?;
            return Ok(Some(value.into_owned()));
        }
    }
    Ok(None)
}

/// The attribute `key`, which must be present; `field` names it in the error.
fn required(element: &BytesStart<'_>, key: &str, field: &str) -> Result<String, SpecError> {
    attribute(element, key)?.ok_or_else(|| {
        urdf_error(format!(
            "<{}> has no '{key}' attribute",
            String::from_utf8_lossy(element.name().as_ref())
        ))
        .at_field(field)
    })
}

/// One finite number.
fn number(text: &str, field: &str) -> Result<f64, SpecError> {
    let [value] = numbers::<1>(text, field)?;
    Ok(value)
}

/// Three finite numbers separated by white space.
fn vector(text: &str, field: &str) -> Result<[f64; 3], SpecError> {
    numbers::<3>(text, field)
}

fn numbers<const N: usize>(text: &str, field: &str) -> Result<[f64; N], SpecError> {
    let malformed = || {
        let what = if N == 1 {
            "a number".to_owned()
        } else {
            format!("{N} numbers separated by spaces")
        };
        urdf_error(format!("expected {what}, got '{text}'")).at_field(field)
    };
    let mut values = [0.0; N];
    let mut words = text.split_whitespace();
    for value in &mut values {
        *value = words
            .next()
            .and_then(|w| w.parse().ok())
            .ok_or_else(malformed)?;
    }
    if words.next().is_some() {
        return Err(malformed());
    }
    finite(&values, field)?;
    Ok(values)
}

fn position(offset: u64) -> usize {
    usize::try_from(offset).unwrap_or(usize::MAX)
}

fn urdf_error(message: impl Into<String>) -> SpecError {
    SpecError::new(SpecErrorKind::Urdf, message)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nested(levels: usize) -> String {
        format!(
            "<robot name=\"r\">\n{}{}</robot>",
            "<x>".repeat(levels),
            "</x>".repeat(levels)
        )
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let error = read(&nested(50_000)).unwrap_err();
        assert!(
            error.message().contains("nest more than 64 deep"),
            "{}",
            error.message()
        );
        assert!(read(&nested(MAX_NESTING - 1)).is_ok());
        assert!(read(&nested(MAX_NESTING)).is_err());
    }

    #[test]
    fn reads_what_the_dynamics_needs_and_skips_the_rest() {
        let text = r#"<?xml version="1.0"?>
<!DOCTYPE robot>
<robot name="r" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:property name="w" value="${2*pi}"/>
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a" foo="${bar}">
    <visual><geometry><mesh filename="package://x.dae"/></geometry></visual>
    <inertial>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      <unknown/>
    </inertial>
    <inertial><mass value="x"/></inertial>
  </link>
  <?processing instruction?>
  <joint name="8" type="continuous" xacro:if="${x}">
    <parent link="a"/><child link="b"/>
    <limit effort="${e}"/>
    <mimic joint="7"/>
    <dynamics damping="0.5"/>
  </joint>
  <gazebo><link name="not-a-link"/></gazebo>
  <transmission name="t"><joint name="8"/></transmission>
</robot>"#;
        let robot = read(text).unwrap();
        assert_eq!(robot.name.as_deref(), Some("r"));
        assert_eq!(robot.links.len(), 1);
        let inertial = robot.links[0].inertial.as_ref().unwrap();
        assert_eq!(inertial.mass, 2.0);
        assert_eq!(robot.joints.len(), 1);
        let joint = &robot.joints[0];
        assert_eq!(joint.joint_type, JointType::Continuous);
        assert_eq!(joint.axis, [1.0, 0.0, 0.0]);
        let mimic = joint.mimic.as_ref().unwrap();
        assert_eq!(
            (mimic.joint.as_str(), mimic.multiplier, mimic.offset),
            ("7", 1.0, 0.0)
        );
        assert_eq!(
            joint.dynamics,
            Some(Dynamics {
                damping: 0.5,
                friction: 0.0
            })
        );
        assert_eq!(
            &text[joint.span.clone()],
            r#"<joint name="8" type="continuous" xacro:if="${x}">"#
        );
    }

    #[test]
    fn malformed_numbers_name_their_field() {
        let text = r#"<robot><joint name="j" type="fixed"><origin xyz="0 0"/></joint></robot>"#;
        let error = read(text).unwrap_err();
        assert_eq!(error.field(), Some("origin.xyz"));
        assert_eq!(
            error.message(),
            "expected 3 numbers separated by spaces, got '0 0'"
        );
        let text =
            r#"<robot><link name="l"><inertial><mass value="inf"/></inertial></link></robot>"#;
        assert_eq!(read(text).unwrap_err().kind(), SpecErrorKind::Physics);
    }
}
