//! Finds NaN and infinities (`.nan`, `.inf`, `1e999`) in a campaign file. serde-saphyr hands
//! them to `f64` fields as they are, and the merge of defaults, scene and grid goes through
//! `serde_json::Value`, which turns a non-finite number into null: without this check
//! `mass: .nan` would silently become the default mass.

use serde::Deserialize;
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// A YAML document with only what the search needs: numbers, keys and structure.
enum Node {
    Float(f64),
    Key(String),
    Other,
    Seq(Vec<Node>),
    Map(Vec<(Node, Node)>),
}

impl<'de> Deserialize<'de> for Node {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Node, D::Error> {
        deserializer.deserialize_any(NodeVisitor)
    }
}

struct NodeVisitor;

impl<'de> Visitor<'de> for NodeVisitor {
    type Value = Node;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any YAML value")
    }
    fn visit_f64<E>(self, v: f64) -> Result<Node, E> {
        Ok(Node::Float(v))
    }
    fn visit_bool<E>(self, _: bool) -> Result<Node, E> {
        Ok(Node::Other)
    }
    fn visit_i64<E>(self, v: i64) -> Result<Node, E> {
        Ok(Node::Key(v.to_string()))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Node, E> {
        Ok(Node::Key(v.to_string()))
    }
    fn visit_i128<E>(self, _: i128) -> Result<Node, E> {
        Ok(Node::Other)
    }
    fn visit_u128<E>(self, _: u128) -> Result<Node, E> {
        Ok(Node::Other)
    }
    fn visit_str<E>(self, v: &str) -> Result<Node, E> {
        Ok(Node::Key(v.to_string()))
    }
    fn visit_unit<E>(self) -> Result<Node, E> {
        Ok(Node::Other)
    }
    fn visit_none<E>(self) -> Result<Node, E> {
        Ok(Node::Other)
    }
    fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<Node, D::Error> {
        Node::deserialize(deserializer)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Node, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        Ok(Node::Seq(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Node, A::Error> {
        let mut entries = Vec::new();
        while let Some(entry) = map.next_entry()? {
            entries.push(entry);
        }
        Ok(Node::Map(entries))
    }
}

/// The field path and value of the first non-finite number in `text` (`scenes[0].material.mass`,
/// `NaN`), if any. Only called on text that already parsed as a campaign.
pub fn first_non_finite(text: &str) -> Option<(String, f64)> {
    let mut options = serde_saphyr::Options::default();
    options.non_finite_float_policy = serde_saphyr::NonFiniteFloatPolicy::PassThrough;
    let node: Node = serde_saphyr::from_str_with_options(text, options).ok()?;
    find(&node, String::new())
}

fn find(node: &Node, path: String) -> Option<(String, f64)> {
    match node {
        Node::Float(v) if !v.is_finite() => Some((path, *v)),
        Node::Seq(items) => items.iter().enumerate().find_map(|(i, item)| find(item, format!("{path}[{i}]"))),
        Node::Map(entries) => entries.iter().find_map(|(key, value)| {
            let key = match key {
                // Grid keys are dotted paths: quoted, as in the other messages.
                Node::Key(k) if k.contains('.') => format!("\"{k}\""),
                Node::Key(k) => k.clone(),
                _ => "?".into(),
            };
            find(value, if path.is_empty() { key } else { format!("{path}.{key}") })
        }),
        _ => None,
    }
}
