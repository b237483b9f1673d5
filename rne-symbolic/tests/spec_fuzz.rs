//! The readers never panic: random bytes, random mutations of valid TOML specs and URDFs
//! (character edits, and for URDF whole elements deleted, duplicated or moved, garbage
//! attributes, truncation, deep nesting) and random expression strings give either a model or
//! an error. A model they do return is well formed.

use std::path::PathBuf;

use proptest::prelude::*;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

fn robot(file: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/robots")
        .join(file);
    std::fs::read_to_string(path).unwrap()
}

/// A spec exercising every convention, inertia form and tree feature.
const CONVENTIONS: &str = r#"name = "all"
gravity = [0, "-g", 0]
[parameters]
g = 9.81
a = "b / 2"
b = 0.4
[[link]]
name = "l1"
joint = "revolute"
rotation = "Rz(q1 - pi/2) * Rx(pi/2)"
position = ["a", 0, 0]
mass = 1
com_from_prev = ["a/2", 0, 0]
inertia = { box = ["a", 0.1, 0.1] }
[[link]]
name = "l2"
joint = "prismatic"
q = "s"
dh = { a = "b", alpha = "pi/2", theta = 0.1 }
mass = 2
com = [0, 0.1, 0]
inertia = [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
[[link]]
name = "l3"
parent = "l1"
joint = "revolute"
mdh = { a = 0.2, alpha = "-pi/2", d = 0.1 }
mass = 0.5
inertia = { xx = 0.01, yy = 0.01, zz = 0.01, xy = 0.001 }
[[link]]
name = "tool"
joint = "fixed"
origin = { xyz = [0, 0, 0.1], rpy = [0, "pi/4", 0] }
mass = 0.1
inertia = { xx = 0, yy = 0, zz = 0 }
[[link]]
name = "wrist"
parent = "l3"
joint = "revolute"
origin = { xyz = [0.1, 0, 0] }
axis = [0, 1, 1]
mass = 0.3
com = [0, 0, 0.05]
inertia = { xx = 0.002, yy = 0.002, zz = 0.001 }
triangle_inequality = false
"#;

/// Fragments that mutations insert: TOML syntax, names, expression pieces, awkward numbers.
const FRAGMENTS: &[&str] = &[
    "\"",
    "[",
    "]",
    "{",
    "}",
    "=",
    ",",
    "\n",
    ".",
    "-",
    "+",
    "*",
    "/",
    "^",
    "(",
    ")",
    "0",
    "1",
    "-1",
    "0.5",
    "1e308",
    "1e-320",
    "nan",
    "inf",
    "true",
    "1979-05-27",
    "q1",
    "q2",
    "s",
    "pi",
    "sqrt(",
    "sin(",
    "Rz(",
    "Rx(q1)",
    "base",
    "l1",
    "link1",
    "link2",
    "[[link]]\n",
    "[parameters]\n",
    "parent = \"l2\"\n",
    "parent = \"link3\"\n",
    "q = \"q1\"\n",
    "q = \"g\"\n",
    "joint = \"fixed\"\n",
    "dh = {}\n",
    "axis = [0, 0, 0]\n",
    "mass = -1\n",
    "\"/0\"",
    "\"sqrt(-1)\"",
    "^0.5",
    "^-3",
    "^1.5",
    "((((",
    "))))",
    "xx = ",
    "box = ",
    "com_from_prev = ",
];

#[derive(Clone, Debug)]
enum Edit {
    Delete { at: usize, len: usize },
    Insert { at: usize, fragment: usize },
    Replace { at: usize, fragment: usize },
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 1..12usize).prop_map(|(at, len)| Edit::Delete { at, len }),
        (any::<usize>(), 0..FRAGMENTS.len())
            .prop_map(|(at, fragment)| Edit::Insert { at, fragment }),
        (any::<usize>(), 0..FRAGMENTS.len())
            .prop_map(|(at, fragment)| Edit::Replace { at, fragment }),
    ]
}

fn mutate(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for edit in edits {
        let n = chars.len().max(1);
        match *edit {
            Edit::Delete { at, len } => {
                let start = at % n;
                let end = (start + len).min(chars.len());
                chars.drain(start.min(end)..end);
            }
            Edit::Insert { at, fragment } => {
                let at = (at % (chars.len() + 1)).min(chars.len());
                chars.splice(at..at, FRAGMENTS[fragment].chars());
            }
            Edit::Replace { at, fragment } => {
                let start = (at % n).min(chars.len());
                let end = (start + FRAGMENTS[fragment].len()).min(chars.len());
                chars.splice(start..end, FRAGMENTS[fragment].chars());
            }
        }
    }
    chars.into_iter().collect()
}

/// What every model the reader returns satisfies.
fn assert_well_formed(model: &RobotModel) {
    for (i, link) in model.links.iter().enumerate() {
        assert!(link.parent.map_or(true, |p| p < i), "parent after child");
        if let Some(k) = link.joint {
            assert_eq!(model.joints[k].link, i);
        }
    }
    assert_eq!(
        model.graph.symbols().joints(),
        model.joint_names().as_slice()
    );
    let numeric = model.to_numeric();
    for link in &numeric.links {
        let values = link
            .rotation
            .concat()
            .into_iter()
            .chain(link.translation)
            .chain(link.axis)
            .chain(link.com);
        assert!(
            values.chain(link.inertia.concat()).all(f64::is_finite),
            "{link:?}"
        );
        assert!(link.mass >= 0.0);
    }
    assert!(numeric.gravity.iter().all(|g| g.is_finite()));
}

fn read(text: &str, symbolic_parameters: bool) {
    if let Ok(model) = read_robot(
        Description::toml(text, "fuzz.toml"),
        &LoadOptions {
            symbolic_parameters,
            ..LoadOptions::default()
        },
    ) {
        assert_well_formed(&model);
    }
}

#[test]
fn the_seed_specs_are_valid() {
    for text in [
        robot("planar-elbow.toml"),
        robot("irb140-3dof.toml"),
        robot("puma560.toml"),
        CONVENTIONS.to_owned(),
    ] {
        for symbolic in [false, true] {
            let model = read_robot(
                Description::toml(&text, "seed.toml"),
                &LoadOptions {
                    symbolic_parameters: symbolic,
                    ..LoadOptions::default()
                },
            )
            .unwrap_or_else(|e| panic!("{e}"));
            assert_well_formed(&model);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        read(&String::from_utf8_lossy(&bytes), false);
    }

    #[test]
    fn mutated_specs_never_panic(
        seed in 0..4usize,
        edits in proptest::collection::vec(edit(), 1..6),
        symbolic in any::<bool>(),
    ) {
        let text = match seed {
            0 => robot("planar-elbow.toml"),
            1 => robot("irb140-3dof.toml"),
            2 => robot("puma560.toml"),
            _ => CONVENTIONS.to_owned(),
        };
        read(&mutate(&text, &edits), symbolic);
    }

    #[test]
    fn random_expressions_never_panic(
        expression in "[-+*/^() .0-9a-zA-Z_]{0,40}",
        field in 0..4usize,
        symbolic in any::<bool>(),
    ) {
        let quoted = expression.replace('"', "");
        let text = match field {
            0 => CONVENTIONS.replacen("mass = 1\n", &format!("mass = \"{quoted}\"\n"), 1),
            1 => CONVENTIONS.replacen("\"Rz(q1 - pi/2) * Rx(pi/2)\"", &format!("\"{quoted}\""), 1),
            2 => CONVENTIONS.replacen("\"b / 2\"", &format!("\"{quoted}\""), 1),
            _ => CONVENTIONS.replacen("theta = 0.1", &format!("theta = \"{quoted}\""), 1),
        };
        read(&text, symbolic);
    }

    #[test]
    fn mutated_urdfs_never_panic(
        seed in 0..3usize,
        edits in proptest::collection::vec(urdf_edit(), 1..6),
        strict in any::<bool>(),
    ) {
        let text = match seed {
            0 => robot("ur5.urdf"),
            1 => robot("panda.urdf"),
            _ => robot("panda-arm.urdf"),
        };
        read_urdf(&mutate_urdf(&text, &edits), strict);
    }

    #[test]
    fn truncated_urdfs_never_panic(seed in 0..3usize, fraction in 0.0..1.0f64) {
        let text = match seed {
            0 => robot("ur5.urdf"),
            1 => robot("panda.urdf"),
            _ => robot("panda-arm.urdf"),
        };
        let mut end = (text.len() as f64 * fraction) as usize;
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        read_urdf(&text[..end], false);
    }
}

/// Fragments that URDF mutations insert: XML syntax, elements the reader reads and ignores,
/// garbage and awkward attribute values.
const URDF_FRAGMENTS: &[&str] = &[
    "<",
    ">",
    "/>",
    "\"",
    "=",
    "&amp;",
    "&bogus;",
    "<!--",
    "-->",
    "<![CDATA[",
    "]]>",
    "<?pi?>",
    "<!DOCTYPE robot>",
    " xyz=\"1 2\"",
    " rpy=\"nan 0 0\"",
    " value=\"-1\"",
    " value=\"1e309\"",
    " link=\"world\"",
    " name=\"8\"",
    " type=\"floating\"",
    " type=\"ball\"",
    " garbage=\"${x}\"",
    " xacro:if=\"1\"",
    "<mimic joint=\"shoulder_pan_joint\"/>",
    "<mimic joint=\"missing\" multiplier=\"x\"/>",
    "<dynamics damping=\"-1\"/>",
    "<axis xyz=\"0 0 0\"/>",
    "<inertial><mass value=\"1\"/></inertial>",
    "<link name=\"world\"/>",
    "<joint name=\"j\" type=\"fixed\"><parent link=\"world\"/><child link=\"world\"/></joint>",
    "<visual><geometry><mesh filename=\"x\"/></geometry></visual>",
    "<x><x><x><x><x><x><x><x></x></x></x></x></x></x></x></x>",
    "</robot>",
    "</link>",
    "</joint>",
];

#[derive(Clone, Debug)]
enum UrdfEdit {
    /// A character-level edit.
    Text(Edit),
    /// Insert a fragment.
    Fragment { at: usize, fragment: usize },
    /// Delete the element starting at the k-th `<` (to its matching end, roughly).
    DeleteElement { at: usize },
    /// Duplicate the k-th `<link` or `<joint` element in place.
    DuplicateElement { at: usize },
    /// Unknown elements nested `depth` deep inside `<robot>`.
    Nest { depth: usize },
}

fn urdf_edit() -> impl Strategy<Value = UrdfEdit> {
    prop_oneof![
        edit().prop_map(UrdfEdit::Text),
        (any::<usize>(), 0..URDF_FRAGMENTS.len())
            .prop_map(|(at, fragment)| UrdfEdit::Fragment { at, fragment }),
        any::<usize>().prop_map(|at| UrdfEdit::DeleteElement { at }),
        any::<usize>().prop_map(|at| UrdfEdit::DuplicateElement { at }),
        (1..200usize).prop_map(|depth| UrdfEdit::Nest { depth }),
    ]
}

/// The byte range of the element opened by the `<` at `start`: up to its `/>` or its closing
/// tag of the same name (the first one, which is right for the URDF elements mutated here).
fn element_at(text: &str, start: usize) -> std::ops::Range<usize> {
    let rest = &text[start..];
    let name: String = rest[1..]
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
        .collect();
    let open_end = rest.find('>').map_or(rest.len(), |e| e + 1);
    if rest[..open_end].ends_with("/>") || name.is_empty() {
        return start..start + open_end;
    }
    let close = format!("</{name}>");
    let end = rest.find(&close).map_or(rest.len(), |e| e + close.len());
    start..start + end
}

fn mutate_urdf(text: &str, edits: &[UrdfEdit]) -> String {
    let mut text = text.to_owned();
    for edit in edits {
        match edit {
            UrdfEdit::Text(edit) => text = mutate(&text, std::slice::from_ref(edit)),
            UrdfEdit::Fragment { at, fragment } => {
                let mut at = at % (text.len() + 1);
                while !text.is_char_boundary(at) {
                    at -= 1;
                }
                text.insert_str(at, URDF_FRAGMENTS[*fragment]);
            }
            UrdfEdit::DeleteElement { at } => {
                let starts: Vec<usize> = text.match_indices('<').map(|(i, _)| i).collect();
                if let Some(&start) = starts.get(at % starts.len().max(1)) {
                    let range = element_at(&text, start);
                    text.replace_range(range, "");
                }
            }
            UrdfEdit::DuplicateElement { at } => {
                let starts: Vec<usize> = text
                    .match_indices("<link")
                    .chain(text.match_indices("<joint"))
                    .map(|(i, _)| i)
                    .collect();
                if let Some(&start) = starts.get(at % starts.len().max(1)) {
                    let range = element_at(&text, start);
                    let copy = text[range.clone()].to_owned();
                    text.insert_str(range.end, &copy);
                }
            }
            UrdfEdit::Nest { depth } => {
                let inside = text
                    .find("<robot")
                    .and_then(|r| text[r..].find('>').map(|e| r + e + 1))
                    .unwrap_or(0);
                let nested = format!("{}{}", "<n>".repeat(*depth), "</n>".repeat(*depth));
                text.insert_str(inside, &nested);
            }
        }
    }
    text
}

fn read_urdf(text: &str, strict: bool) {
    let options = LoadOptions {
        strict,
        ..LoadOptions::default()
    };
    if let Ok(model) = read_robot(Description::urdf(text, "fuzz.urdf"), &options) {
        assert_well_formed(&model);
    }
}

#[test]
fn the_seed_urdfs_are_valid() {
    for file in ["ur5.urdf", "panda.urdf", "panda-arm.urdf"] {
        let model = read_robot(
            Description::urdf(&robot(file), file),
            &LoadOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_well_formed(&model);
    }
}
