//! The TOML text as a tree that remembers where every key and value was written, so that
//! errors can name the line; and the typed accessors the spec reader walks it with.
//!
//! The `toml` crate reports positions through its `Spanned` wrapper; the tree asks for a span
//! at every key and value and accepts a value without one (tables created implicitly by dotted
//! keys have none). Keys are kept in file order.

use std::fmt;
use std::ops::Range;

use serde::de::{self, Deserialize, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::error::{SpecError, SpecErrorKind};

/// Byte range of a key or value in the TOML text, when the parser knows it.
pub(crate) type Span = Option<Range<usize>>;

/// A TOML value and where it was written.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Item {
    pub(crate) value: Value,
    pub(crate) span: Span,
}

/// The TOML value types.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    String(String),
    Integer(i64),
    Float(f64),
    Boolean(bool),
    Datetime,
    Array(Vec<Item>),
    Table(Table),
}

/// A TOML table: its entries in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Table {
    entries: Vec<Entry>,
}

/// One `key = value` of a table.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub(crate) key: String,
    pub(crate) key_span: Span,
    pub(crate) item: Item,
}

/// Parses TOML text into its root table.
pub(crate) fn parse(text: &str) -> Result<Table, SpecError> {
    toml::from_str::<Root>(text)
        .map(|root| root.0)
        .map_err(|error| {
            SpecError::new(
                SpecErrorKind::Syntax,
                format!(
                    "invalid TOML: {}",
                    error.message().trim_end().replace('\n', "; ")
                ),
            )
            .at_span(error.span())
        })
}

impl Table {
    /// The entries in file order.
    pub(crate) fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The value of `key`.
    pub(crate) fn get(&self, key: &str) -> Option<&Item> {
        self.entries.iter().find(|e| e.key == key).map(|e| &e.item)
    }

    /// Whether `key` is present.
    pub(crate) fn contains(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// Rejects every key that is not in `allowed`. `path` is the table's field path (`""` for
    /// a top-level or link table), used to name the offending field.
    pub(crate) fn check_keys(&self, allowed: &[&str], path: &str) -> Result<(), SpecError> {
        match self
            .entries
            .iter()
            .find(|e| !allowed.contains(&e.key.as_str()))
        {
            None => Ok(()),
            Some(entry) => {
                let within = if path.is_empty() {
                    String::new()
                } else {
                    format!(" in '{path}'")
                };
                Err(SpecError::new(
                    SpecErrorKind::Format,
                    format!(
                        "unknown key '{}'{within} (expected one of: {})",
                        entry.key,
                        allowed.join(", ")
                    ),
                )
                .at_field(join_path(path, &entry.key))
                .at_span(entry.key_span.clone()))
            }
        }
    }

    /// Where the value at a field path (`inertia.xy`, `com[1]`, `inertia[0][2]`) was written;
    /// the deepest part of the path that exists when the whole does not.
    pub(crate) fn span_of(&self, path: &str) -> Span {
        let mut table = Some(self);
        let mut found = None;
        for segment in path.split('.') {
            let mut parts = segment.split('[');
            let key = parts.next().unwrap_or_default();
            let Some(entry) = table.and_then(|t| t.entries.iter().find(|e| e.key == key)) else {
                break;
            };
            let mut item = &entry.item;
            found = item
                .span
                .clone()
                .or_else(|| entry.key_span.clone())
                .or(found);
            for index in parts {
                let element = index
                    .trim_end_matches(']')
                    .parse::<usize>()
                    .ok()
                    .and_then(|i| match &item.value {
                        Value::Array(elements) => elements.get(i),
                        _ => None,
                    });
                let Some(element) = element else { break };
                item = element;
                found = item.span.clone().or(found);
            }
            table = match &item.value {
                Value::Table(t) => Some(t),
                _ => None,
            };
        }
        found
    }

    /// The value of a required key.
    pub(crate) fn required(&self, key: &str, path: &str) -> Result<&Item, SpecError> {
        self.get(key).ok_or_else(|| {
            SpecError::new(
                SpecErrorKind::Format,
                format!("missing required key '{key}'"),
            )
            .at_field(join_path(path, key))
        })
    }
}

/// `path.key`, or `key` for an empty path.
pub(crate) fn join_path(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_owned()
    } else {
        format!("{path}.{key}")
    }
}

impl Item {
    /// The string value, or an error naming `field`.
    pub(crate) fn as_str(&self, field: &str) -> Result<&str, SpecError> {
        match &self.value {
            Value::String(s) => Ok(s),
            _ => Err(self.type_error("a string", field)),
        }
    }

    /// The boolean value, or an error naming `field`.
    pub(crate) fn as_bool(&self, field: &str) -> Result<bool, SpecError> {
        match self.value {
            Value::Boolean(b) => Ok(b),
            _ => Err(self.type_error("true or false", field)),
        }
    }

    /// The table value, or an error naming `field`.
    pub(crate) fn as_table(&self, field: &str) -> Result<&Table, SpecError> {
        match &self.value {
            Value::Table(t) => Ok(t),
            _ => Err(self.type_error("a table", field)),
        }
    }

    /// The elements of an array value, or an error naming `field`.
    pub(crate) fn as_array(&self, field: &str) -> Result<&[Item], SpecError> {
        match &self.value {
            Value::Array(a) => Ok(a),
            _ => Err(self.type_error("an array", field)),
        }
    }

    /// An array of exactly `N` elements, or an error naming `field`.
    pub(crate) fn as_fixed_array<const N: usize>(
        &self,
        field: &str,
    ) -> Result<[&Item; N], SpecError> {
        let elements = self.as_array(field)?;
        let mut out = Vec::with_capacity(N);
        out.extend(elements.iter());
        out.try_into().map_err(|_| {
            SpecError::new(
                SpecErrorKind::Format,
                format!(
                    "expected an array of {N} elements, found {}",
                    elements.len()
                ),
            )
            .at_field(field)
            .at_span(self.span.clone())
        })
    }

    /// A "wrong type" error naming `field`.
    pub(crate) fn type_error(&self, expected: &str, field: &str) -> SpecError {
        SpecError::new(
            SpecErrorKind::Format,
            format!("expected {expected}, found {}", self.value),
        )
        .at_field(field)
        .at_span(self.span.clone())
    }
}

impl fmt::Display for Value {
    /// The value's type with an article, for messages: `a string`, `an integer`, ...
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Value::String(_) => "a string",
            Value::Integer(_) => "an integer",
            Value::Float(_) => "a float",
            Value::Boolean(_) => "a boolean",
            Value::Datetime => "a date-time",
            Value::Array(_) => "an array",
            Value::Table(_) => "a table",
        })
    }
}

// The private protocol of `serde_spanned` (stable across toml 0.5 to 0.9): a value asked for as
// this struct arrives as a map of start, end and the value itself, when its span is known.
const SPANNED: &str = "$__serde_spanned_private_Spanned";
const SPAN_START: &str = "$__serde_spanned_private_start";
const SPAN_END: &str = "$__serde_spanned_private_end";
const SPAN_VALUE: &str = "$__serde_spanned_private_value";
const SPANNED_FIELDS: &[&str] = &[SPAN_START, SPAN_END, SPAN_VALUE];
// A TOML date-time arrives as a map with this single key.
const DATETIME: &str = "$__toml_private_datetime";

struct Root(Table);

impl<'de> Deserialize<'de> for Root {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Root, D::Error> {
        match deserializer.deserialize_any(ValueVisitor)? {
            Value::Table(table) => Ok(Root(table)),
            other => Err(de::Error::custom(format!(
                "expected a table at the top level, found {other}"
            ))),
        }
    }
}

impl<'de> Deserialize<'de> for Item {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Item, D::Error> {
        deserializer.deserialize_struct(SPANNED, SPANNED_FIELDS, ItemVisitor)
    }
}

struct Key {
    name: String,
    span: Span,
}

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Key, D::Error> {
        deserializer.deserialize_struct(SPANNED, SPANNED_FIELDS, KeyVisitor)
    }
}

/// Reads the rest of a span map whose first key (`SPAN_START`) has been read.
fn read_spanned<'de, A: MapAccess<'de>, T: Deserialize<'de>>(
    mut map: A,
) -> Result<(T, Range<usize>), A::Error> {
    let start: usize = map.next_value()?;
    map.next_key::<IgnoredAny>()?;
    let end: usize = map.next_value()?;
    map.next_key::<IgnoredAny>()?;
    let value: T = map.next_value()?;
    Ok((value, start..end))
}

/// Reads a table whose first key has been read.
fn read_table<'de, A: MapAccess<'de>>(first: Key, mut map: A) -> Result<Table, A::Error> {
    let mut entries = vec![Entry {
        key: first.name,
        key_span: first.span,
        item: map.next_value()?,
    }];
    while let Some(key) = map.next_key::<Key>()? {
        entries.push(Entry {
            key: key.name,
            key_span: key.span,
            item: map.next_value()?,
        });
    }
    Ok(Table { entries })
}

/// Reads a map that is a table or a date-time (never a span map).
fn read_map<'de, A: MapAccess<'de>>(first: Option<Key>, mut map: A) -> Result<Value, A::Error> {
    match first {
        None => Ok(Value::Table(Table::default())),
        Some(key) if key.name == DATETIME => {
            map.next_value::<IgnoredAny>()?;
            Ok(Value::Datetime)
        }
        Some(key) => read_table(key, map).map(Value::Table),
    }
}

struct ValueVisitor;

impl<'de> Visitor<'de> for ValueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a TOML value")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Boolean(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Value, E> {
        Ok(Value::Integer(v))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Value, E> {
        i64::try_from(v)
            .map(Value::Integer)
            .map_err(|_| E::custom(format!("integer {v} is too large")))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Value, E> {
        Ok(Value::Float(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element::<Item>()? {
            items.push(item);
        }
        Ok(Value::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let first = map.next_key::<Key>()?;
        read_map(first, map)
    }
}

impl<'de> Deserialize<'de> for Value {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(ValueVisitor)
    }
}

struct ItemVisitor;

impl ItemVisitor {
    fn bare<E>(value: Result<Value, E>) -> Result<Item, E> {
        value.map(|value| Item { value, span: None })
    }
}

impl<'de> Visitor<'de> for ItemVisitor {
    type Value = Item;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a TOML value")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_i64(v))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_u64(v))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_f64(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_str(v))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Item, E> {
        Self::bare(ValueVisitor.visit_string(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Item, A::Error> {
        Self::bare(ValueVisitor.visit_seq(seq))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Item, A::Error> {
        let first = map.next_key::<Key>()?;
        if first.as_ref().is_some_and(|k| k.name == SPAN_START) {
            let (value, span) = read_spanned::<A, Value>(map)?;
            return Ok(Item {
                value,
                span: Some(span),
            });
        }
        Self::bare(read_map(first, map))
    }
}

struct KeyVisitor;

impl<'de> Visitor<'de> for KeyVisitor {
    type Value = Key;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a TOML key")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Key, E> {
        Ok(Key {
            name: v.to_owned(),
            span: None,
        })
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Key, E> {
        Ok(Key {
            name: v,
            span: None,
        })
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Key, A::Error> {
        match map.next_key::<String>()? {
            Some(first) if first == SPAN_START => {
                let (name, span) = read_spanned::<A, String>(map)?;
                Ok(Key {
                    name,
                    span: Some(span),
                })
            }
            _ => Err(de::Error::custom("expected a TOML key")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_of(text: &str, span: &Span) -> usize {
        let start = span.as_ref().map(|s| s.start).unwrap_or_default();
        text[..start].matches('\n').count() + 1
    }

    #[test]
    fn keeps_order_values_and_spans() {
        let text = "name = \"x\"\n[parameters]\nb = 2\na = \"b * 3\"\n\n[[link]]\nmass = 1.5\ninertia = { xx = 1 }\n";
        let root = parse(text).unwrap();
        let keys: Vec<&str> = root.entries().iter().map(|e| e.key.as_str()).collect();
        assert_eq!(keys, ["name", "parameters", "link"]);
        let parameters = root
            .get("parameters")
            .unwrap()
            .as_table("parameters")
            .unwrap();
        let names: Vec<&str> = parameters
            .entries()
            .iter()
            .map(|e| e.key.as_str())
            .collect();
        assert_eq!(names, ["b", "a"]);
        assert_eq!(parameters.get("b").unwrap().value, Value::Integer(2));
        assert_eq!(line_of(text, &parameters.get("a").unwrap().span), 4);
        assert_eq!(line_of(text, &parameters.entries()[1].key_span), 4);
        let links = root.get("link").unwrap().as_array("link").unwrap();
        let link = links[0].as_table("link").unwrap();
        assert_eq!(link.get("mass").unwrap().value, Value::Float(1.5));
        assert_eq!(line_of(text, &link.get("mass").unwrap().span), 7);
        let inertia = link.get("inertia").unwrap().as_table("inertia").unwrap();
        assert_eq!(line_of(text, &inertia.entries()[0].key_span), 8);
    }

    #[test]
    fn field_paths_find_their_spans() {
        let text = "com = [\n  1,\n  2,\n]\ninertia = [[1, 0, 0],\n  [0, 1, 0], [0, 0, 1]]\n[dh]\na = 1\ntheta = 2\n";
        let root = parse(text).unwrap();
        assert_eq!(line_of(text, &root.span_of("com[1]")), 3);
        assert_eq!(line_of(text, &root.span_of("com[7]")), 1);
        assert_eq!(line_of(text, &root.span_of("inertia[1][2]")), 6);
        assert_eq!(line_of(text, &root.span_of("dh.theta")), 9);
        assert_eq!(line_of(text, &root.span_of("dh.alpha")), 7);
        assert_eq!(root.span_of("nothing"), None);
    }

    #[test]
    fn dotted_keys_and_dates_are_read() {
        let text = "[[link]]\ninertia.xx = 1\ninertia.yy = 2\nwhen = 1979-05-27\n";
        let root = parse(text).unwrap();
        let links = root.get("link").unwrap().as_array("link").unwrap();
        let link = links[0].as_table("link").unwrap();
        let inertia = link.get("inertia").unwrap().as_table("inertia").unwrap();
        assert_eq!(inertia.get("yy").unwrap().value, Value::Integer(2));
        assert_eq!(line_of(text, &inertia.get("yy").unwrap().span), 3);
        assert_eq!(link.get("when").unwrap().value, Value::Datetime);
    }

    #[test]
    fn syntax_errors_carry_their_position() {
        let text = "a = 1\nb = = 2\nc = 3\n";
        let error = parse(text).unwrap_err().locate("f.toml", text);
        assert_eq!(error.kind(), SpecErrorKind::Syntax);
        assert!(
            error.to_string().starts_with("f.toml:2: invalid TOML: "),
            "{error}"
        );
        assert!(!error.to_string().contains('\n'), "{error}");
    }

    #[test]
    fn unknown_keys_are_named() {
        let text = "a = 1\ncolour = 2\n";
        let root = parse(text).unwrap();
        let error = root
            .check_keys(&["a"], "")
            .unwrap_err()
            .locate("f.toml", text);
        assert_eq!(
            error.to_string(),
            "f.toml:2: field 'colour': unknown key 'colour' (expected one of: a)"
        );
    }
}
