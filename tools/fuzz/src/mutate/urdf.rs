//! URDF-aware mutations, on the text: `<link>` and `<joint>` elements removed, duplicated
//! (with their name or a fresh one) and renamed; joints relinked (to another link, to their
//! own child, to a missing link: cycles, second parents and orphans) or reversed; joint types
//! changed to every URDF type and to garbage; attribute values replaced by odd numbers (whole
//! or one component), removed, duplicated or given entities; child elements (`<origin>`,
//! `<axis>`, `<inertial>`, `<mass>`, `<parent>`, ...) removed or added; elements nested deep;
//! the `<robot>` root broken.

use std::ops::Range;

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::{pick, Applied};
use crate::odd;

/// An element of the text: its tag, its whole range and the range of its opening tag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Element {
    /// The tag name.
    pub tag: String,
    /// From `<` to the end of its closing tag (or of the opening tag, if it is empty).
    pub range: Range<usize>,
    /// The opening tag.
    pub open: Range<usize>,
}

impl Element {
    /// The value of the opening tag's attribute `key`, if present.
    pub fn attribute<'a>(&self, text: &'a str, key: &str) -> Option<&'a str> {
        attributes(text, self.open.clone())
            .into_iter()
            .find(|a| a.key == key)
            .map(|a| &text[a.value])
    }

    /// The element's `name` attribute, or `?` for none.
    pub fn name(&self, text: &str) -> String {
        self.attribute(text, "name").unwrap_or("?").to_owned()
    }
}

/// An attribute: its name and the range of its value (inside the quotes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attribute {
    /// The attribute's name.
    pub key: String,
    /// The range of its value.
    pub value: Range<usize>,
}

/// The elements `<tag ...>` of `text`, each to the first closing tag of its name after it.
pub fn elements(text: &str, tag: &str) -> Vec<Element> {
    let opening = format!("<{tag}");
    let closing = format!("</{tag}>");
    text.match_indices(&opening)
        .filter(|(at, _)| {
            let next = text[at + opening.len()..].chars().next();
            next.is_some_and(|c| c.is_whitespace() || c == '>' || c == '/')
        })
        .map(|(start, _)| {
            let open_end = text[start..]
                .find('>')
                .map_or(text.len(), |e| start + e + 1);
            let end = if text[start..open_end].ends_with("/>") {
                open_end
            } else {
                text[open_end..]
                    .find(&closing)
                    .map_or(text.len(), |e| open_end + e + closing.len())
            };
            Element {
                tag: tag.to_owned(),
                range: start..end,
                open: start..open_end,
            }
        })
        .collect()
}

/// The attributes `key="value"` (or `'value'`) within `range` of `text`.
pub fn attributes(text: &str, range: Range<usize>) -> Vec<Attribute> {
    let bytes = text.as_bytes();
    let mut found = Vec::new();
    let mut at = range.start;
    while at + 1 < range.end {
        let quote = bytes[at + 1];
        if bytes[at] == b'=' && (quote == b'"' || quote == b'\'') {
            let key_start = text[..at]
                .rfind(|c: char| c.is_whitespace() || c == '<')
                .map_or(0, |k| k + 1);
            let value_start = at + 2;
            if let Some(len) = text[value_start..range.end].find(quote as char) {
                found.push(Attribute {
                    key: text[key_start..at].to_owned(),
                    value: value_start..value_start + len,
                });
                at = value_start + len + 1;
                continue;
            }
        }
        at += 1;
    }
    found
}

/// The `<link>` and `<joint>` elements of `text`.
fn named_elements(text: &str) -> Vec<Element> {
    let mut all = elements(text, "link");
    all.extend(elements(text, "joint"));
    all
}

/// The innermost `<link>` or `<joint>` containing byte `at`.
fn owner(text: &str, at: usize) -> Option<Element> {
    named_elements(text)
        .into_iter()
        .filter(|e| e.range.contains(&at))
        .min_by_key(|e| e.range.len())
}

/// The field a reader error names for attribute `key` of the element `tag`: the element for
/// attributes that are its only value (`<mass value>`, `<parent link>`, `<mimic joint>`), else
/// the attribute.
fn field(tag: &str, key: &str) -> String {
    match key {
        "value" | "link" | "joint" => tag.to_owned(),
        _ => key.to_owned(),
    }
}

/// The tag whose opening `<` is the last one before `at`.
fn tag_before(text: &str, at: usize) -> String {
    let start = text[..at].rfind('<').map_or(0, |s| s + 1);
    text[start..]
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
        .collect()
}

/// Applies one random URDF mutation to `text`; chains are at most `longest` joints long.
pub fn mutate(rng: &mut ChaCha8Rng, text: &mut String, longest: usize) -> Applied {
    let applied = match rng.gen_range(0..15) {
        0 => remove_element(rng, text),
        1 => duplicate_element(rng, text),
        2 | 3 => relink(rng, text),
        4 => change_type(rng, text),
        5 | 6 => odd_value(rng, text),
        7 => drop_or_double_attribute(rng, text),
        8 => remove_child(rng, text),
        9 => add_child(rng, text),
        10 => rename(rng, text),
        11 => entity(rng, text),
        12 => nest(rng, text),
        13 => long_chain(rng, text, longest),
        _ => break_root(rng, text),
    };
    applied.unwrap_or_else(|| Applied::anywhere("nothing to mutate"))
}

fn remove_element(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = named_elements(text);
    let element = pick_some(rng, &all)?;
    let name = element.name(text);
    text.replace_range(element.range.clone(), "");
    Some(Applied::at(
        format!("remove {} '{name}'", element.tag),
        &name,
        &element.tag,
    ))
}

fn duplicate_element(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = named_elements(text);
    let element = pick_some(rng, &all)?;
    let name = element.name(text);
    let mut copy = text[element.range.clone()].to_owned();
    let renamed = rng.gen_bool(0.5);
    if renamed {
        copy = copy.replacen(&format!("name=\"{name}\""), "name=\"copy\"", 1);
    }
    let at = if rng.gen_bool(0.5) {
        element.range.end
    } else {
        element.range.start
    };
    text.insert_str(at, &copy);
    let what = if renamed { " renamed 'copy'" } else { "" };
    Some(Applied::at(
        format!("duplicate {} '{name}'{what}", element.tag),
        &name,
        "name",
    ))
}

/// Points a joint's `<parent>` or `<child>` at another link, its own child or parent, a
/// missing or empty name; or swaps them.
fn relink(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let joints = elements(text, "joint");
    let joint = pick_some(rng, &joints)?;
    let name = joint.name(text);
    let end = if rng.gen_bool(0.5) { "parent" } else { "child" };
    let link_attribute = elements(&text[joint.range.clone()], end)
        .first()
        .and_then(|e| {
            attributes(text, shift(&e.open, joint.range.start))
                .into_iter()
                .find(|a| a.key == "link")
        })?;
    let links: Vec<String> = elements(text, "link")
        .iter()
        .map(|l| l.name(text))
        .collect();
    let other = |what| {
        elements(&text[joint.range.clone()], what)
            .first()
            .and_then(|e| {
                attributes(text, shift(&e.open, joint.range.start))
                    .into_iter()
                    .find(|a| a.key == "link")
            })
            .map(|a| text[a.value].to_owned())
    };
    let target = match rng.gen_range(0..4) {
        0 if !links.is_empty() => pick(rng, &links).clone(),
        1 => other(if end == "parent" { "child" } else { "parent" })?,
        2 => pick(rng, odd::NAMES).to_string(),
        _ => format!("{name}-orphan"),
    };
    text.replace_range(link_attribute.value, &target);
    Some(Applied::at(
        format!("relink the {end} of joint '{name}' to '{target}'"),
        &name,
        end,
    ))
}

fn shift(range: &Range<usize>, by: usize) -> Range<usize> {
    range.start + by..range.end + by
}

fn change_type(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let joints = elements(text, "joint");
    let joint = pick_some(rng, &joints)?;
    let name = joint.name(text);
    let kind = attributes(text, joint.open.clone())
        .into_iter()
        .find(|a| a.key == "type")?;
    let new = *pick(rng, odd::URDF_JOINT_TYPES);
    text.replace_range(kind.value, new);
    Some(Applied::at(
        format!("type of joint '{name}' to {new:?}"),
        &name,
        "type",
    ))
}

/// Replaces an attribute's value, or one of its space-separated numbers, by an odd number.
fn odd_value(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = attributes(text, 0..text.len());
    let attribute = pick_some(rng, &all)?;
    let new = *pick(rng, odd::NUMBERS);
    let value = &text[attribute.value.clone()];
    let words: Vec<&str> = value.split_whitespace().collect();
    let replaced = if words.len() > 1 && rng.gen_bool(0.6) {
        let k = rng.gen_range(0..words.len());
        let mut words: Vec<String> = words.iter().map(|w| w.to_string()).collect();
        words[k] = new.to_owned();
        words.join(" ")
    } else {
        new.to_owned()
    };
    let tag = tag_before(text, attribute.value.start);
    let element = owner(text, attribute.value.start).map(|e| e.name(text));
    text.replace_range(attribute.value.clone(), &replaced);
    let field = field(&tag, &attribute.key);
    let description = format!("<{tag} {}={replaced:?}>", attribute.key);
    Some(match element {
        Some(element) if tag != "link" && tag != "joint" || attribute.key != "name" => {
            Applied::at(description, &element, &field)
        }
        _ => Applied::anywhere(description),
    })
}

fn drop_or_double_attribute(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = attributes(text, 0..text.len());
    let attribute = pick_some(rng, &all)?;
    let key_start = attribute.value.start - attribute.key.len() - 2;
    let whole = key_start..attribute.value.end + 1;
    let tag = tag_before(text, attribute.value.start);
    let element = owner(text, attribute.value.start).map(|e| e.name(text));
    let double = rng.gen_bool(0.5);
    if double {
        let copy = format!(" {}", &text[whole.clone()]);
        text.insert_str(whole.end, &copy);
    } else {
        text.replace_range(whole, "");
    }
    let verb = if double { "duplicate" } else { "remove" };
    let description = format!("{verb} attribute {} of <{tag}>", attribute.key);
    Some(match element {
        Some(element) => Applied::at(description, &element, &field(&tag, &attribute.key)),
        None => Applied::anywhere(description),
    })
}

/// The child elements mutations remove, and the ones they add to a joint and to a link.
const CHILDREN: &[&str] = &[
    "origin", "axis", "inertial", "mass", "inertia", "parent", "child", "mimic", "dynamics",
    "limit",
];

fn remove_child(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let tag = *pick(rng, CHILDREN);
    let all = elements(text, tag);
    let child = pick_some(rng, &all)?;
    let element = owner(text, child.range.start).map(|e| e.name(text));
    text.replace_range(child.range.clone(), "");
    let description = format!("remove a <{tag}>");
    Some(match element {
        Some(element) => Applied::at(description, &element, tag),
        None => Applied::anywhere(description),
    })
}

fn add_child(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = named_elements(text);
    let element = pick_some(rng, &all)?;
    if text[element.open.clone()].ends_with("/>") {
        return None;
    }
    let name = element.name(text);
    let joints: Vec<String> = elements(text, "joint")
        .iter()
        .map(|j| j.name(text))
        .collect();
    let number = *pick(rng, odd::NUMBERS);
    let (child, field) = if element.tag == "joint" {
        match rng.gen_range(0..5) {
            0 => {
                let leader = match rng.gen_range(0..3) {
                    0 => name.clone(),
                    1 if !joints.is_empty() => pick(rng, &joints).clone(),
                    _ => "ghost".to_owned(),
                };
                let (m, o) = (number, *pick(rng, odd::NUMBERS));
                let child =
                    format!("<mimic joint=\"{leader}\" multiplier=\"{m}\" offset=\"{o}\"/>");
                (child, "mimic")
            }
            1 => (format!("<axis xyz=\"{}\"/>", number), "axis"),
            2 => (format!("<dynamics damping=\"{}\"/>", number), "damping"),
            3 => (format!("<origin rpy=\"{}\"/>", number), "rpy"),
            _ => (format!("<parent link=\"{name}\"/>"), "parent"),
        }
    } else {
        let mass = number;
        let child = match rng.gen_range(0..4) {
            0 => format!("<inertial><mass value=\"{mass}\"/></inertial>"),
            1 => "<inertial><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>".to_owned(),
            2 => format!("<inertial><mass value=\"1\"/><inertia ixx=\"{mass}\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>"),
            _ => "<inertial/>".to_owned(),
        };
        (child, "inertial")
    };
    // The first of repeated elements counts: put it first.
    text.insert_str(element.open.end, &child);
    Some(Applied::at(
        format!("add {child} to {} '{name}'", element.tag),
        &name,
        field,
    ))
}

fn rename(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = named_elements(text);
    let element = pick_some(rng, &all)?;
    let name = element.name(text);
    let attribute = attributes(text, element.open.clone())
        .into_iter()
        .find(|a| a.key == "name")?;
    let others: Vec<String> = all.iter().map(|e| e.name(text)).collect();
    let new = if rng.gen_bool(0.5) {
        pick(rng, &others).clone()
    } else {
        pick(rng, odd::NAMES).to_string()
    };
    text.replace_range(attribute.value, &new);
    Some(Applied::at(
        format!("rename {} '{name}' to '{new}'", element.tag),
        &new,
        "name",
    ))
}

/// Entities in an attribute value: defined ones, an undefined one, character references to
/// NUL, a surrogate and beyond Unicode.
const ENTITIES: &[&str] = &[
    "&lt;",
    "&amp;",
    "&bogus;",
    "&#0;",
    "&#xD800;",
    "&#99999999;",
    "&#x31;",
    "&",
    "&#;",
];

fn entity(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let all = attributes(text, 0..text.len());
    let attribute = pick_some(rng, &all)?;
    let at = rng.gen_range(attribute.value.start..=attribute.value.end);
    let at = super::floor_boundary(text, at).max(attribute.value.start);
    let entity = *pick(rng, ENTITIES);
    let tag = tag_before(text, attribute.value.start);
    let element = owner(text, attribute.value.start).map(|e| e.name(text));
    text.insert_str(at, entity);
    let description = format!("{entity} in <{tag} {}>", attribute.key);
    Some(match element {
        Some(element) if attribute.key != "name" => {
            Applied::at(description, &element, &field(&tag, &attribute.key))
        }
        _ => Applied::anywhere(description),
    })
}

fn nest(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let depth = *pick(rng, &[2, 10, 62, 63, 64, 65, 1000, 100_000]);
    let starts: Vec<usize> = text.match_indices('<').map(|(i, _)| i).collect();
    let at = *pick_some(rng, &starts)?;
    // Deep `<link>` and `<joint>` nests stay shallow enough for the next mutation's scans.
    let tag = match depth {
        100_000 => "n",
        _ => *pick(rng, &["n", "link", "inertial", "joint"]),
    };
    let nested = format!(
        "{}{}",
        format!("<{tag}>").repeat(depth),
        format!("</{tag}>").repeat(depth)
    );
    text.insert_str(at, &nested);
    Some(Applied::anywhere(format!("<{tag}> nested {depth} deep")))
}

/// A joint and its child link copied many times, each copy hanging from the previous one and
/// (sometimes) mimicking it: a long chain for the reader's and the tree's scaling.
fn long_chain(rng: &mut ChaCha8Rng, text: &mut String, longest: usize) -> Option<Applied> {
    let joints = elements(text, "joint");
    let joint = pick_some(rng, &joints)?.clone();
    let name = joint.name(text);
    let child = elements(&text[joint.range.clone()], "child")
        .first()
        .and_then(|e| {
            attributes(text, shift(&e.open, joint.range.start))
                .into_iter()
                .find(|a| a.key == "link")
        })
        .map(|a| text[a.value].to_owned())?;
    let copies = super::chain_length(rng, longest);
    let mimic = rng.gen_bool(0.3);
    let mut chain = String::new();
    for k in 0..copies {
        let parent = if k == 0 {
            child.clone()
        } else {
            format!("chain{}", k - 1)
        };
        let follows = if mimic && k > 0 {
            format!("<mimic joint=\"chainjoint{}\" multiplier=\"0.5\"/>", k - 1)
        } else {
            String::new()
        };
        chain.push_str(&format!(
            "<link name=\"chain{k}\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n<joint name=\"chainjoint{k}\" type=\"revolute\"><parent link=\"{parent}\"/><child link=\"chain{k}\"/><axis xyz=\"0 0 1\"/>{follows}</joint>\n"
        ));
    }
    text.insert_str(joint.range.end, &chain);
    Some(Applied::at(
        format!(
            "a chain of {copies} joints{} after joint '{name}'",
            if mimic { " mimicking each other" } else { "" }
        ),
        &name,
        "child",
    ))
}

fn break_root(rng: &mut ChaCha8Rng, text: &mut String) -> Option<Applied> {
    let description = match rng.gen_range(0..5) {
        0 => {
            let end = text.rfind("</robot>")?;
            text.replace_range(end..end + "</robot>".len(), "");
            "remove </robot>"
        }
        1 => {
            let copy = text.clone();
            text.push_str(&copy);
            "the document twice"
        }
        2 => {
            text.insert_str(0, "text before the root\n");
            "text before the root"
        }
        3 => {
            let start = text.find("<robot")?;
            text.replace_range(start..start + "<robot".len(), "<robots");
            "root renamed <robots>"
        }
        _ => {
            text.insert_str(0, "<?xml version=\"1.0\" encoding=\"latin-1\"?>\n");
            "an XML declaration naming another encoding"
        }
    };
    Some(Applied::anywhere(description))
}

fn pick_some<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> Option<&'a T> {
    (!items.is_empty()).then(|| pick(rng, items))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    const URDF: &str = r#"<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
</robot>"#;

    #[test]
    fn finds_elements_and_attributes() {
        let joints = elements(URDF, "joint");
        assert_eq!(joints.len(), 1);
        assert_eq!(joints[0].name(URDF), "j");
        assert!(URDF[joints[0].range.clone()].ends_with("</joint>"));
        let links = elements(URDF, "link");
        assert_eq!(links.len(), 2);
        assert_eq!(&URDF[links[1].range.clone()], "<link name=\"b\"/>");
        let keys: Vec<String> = attributes(URDF, joints[0].range.clone())
            .into_iter()
            .map(|a| a.key)
            .collect();
        assert_eq!(keys, ["name", "type", "link", "link", "xyz"]);
        assert_eq!(
            owner(URDF, URDF.find("xyz").unwrap()).unwrap().name(URDF),
            "j"
        );
    }

    #[test]
    fn every_mutation_kind_changes_the_text_and_replays() {
        let mut kinds = std::collections::HashSet::new();
        let mut changed = 0;
        for seed in 0..400 {
            let run = || {
                let mut text = URDF.to_owned();
                let applied = mutate(&mut ChaCha8Rng::seed_from_u64(seed), &mut text, 3000);
                (text, applied)
            };
            let (text, applied) = run();
            assert_eq!((text.clone(), applied.clone()), run());
            let kind: String = applied.description.split(' ').take(1).collect();
            kinds.insert(kind);
            changed += usize::from(text != URDF);
        }
        assert!(changed > 360, "{changed}");
        assert!(kinds.len() >= 10, "{kinds:?}");
    }
}
