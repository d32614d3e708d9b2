//! A JSON value as serde_json's parser hands it over, read by one
//! `deserialize_any` ([`Json`]): the page's reader of weights files
//! (`networks::reader`) takes a file's fields from it, and the number
//! reader of the arm, limits and obstacle syntax (`arm::number`) reads one
//! number through it. One monomorphisation of serde_json's parser serves
//! both. A second, for `f64`, brought serde's invalid-type error path with
//! it (serde_json's `make_error` and its string searcher, `Unexpected`'s
//! Display, `str`'s Debug): 3.5 KB of the page's module gzipped, 150,104
//! -> 146,636 B (`twiggy diff`, 2 December).

use std::fmt;

use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};

/// A JSON value as serde_json's parser hands it over; an object keeps its
/// fields in order as pairs (a map type would bring its code along).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Json {
    Null,
    Bool(bool),
    /// A non-negative integer.
    Uint(u64),
    /// A negative integer.
    Int(i64),
    Float(f64),
    Str(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

impl Json {
    /// The value as a number, if it is one.
    pub(crate) fn number(&self) -> Option<f64> {
        match *self {
            Json::Float(x) => Some(x),
            Json::Uint(x) => Some(x as f64),
            Json::Int(x) => Some(x as f64),
            _ => None,
        }
    }
}

struct JsonVisitor;

impl<'de> Visitor<'de> for JsonVisitor {
    type Value = Json;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_unit<E>(self) -> Result<Json, E> {
        Ok(Json::Null)
    }
    fn visit_bool<E>(self, b: bool) -> Result<Json, E> {
        Ok(Json::Bool(b))
    }
    fn visit_u64<E>(self, x: u64) -> Result<Json, E> {
        Ok(Json::Uint(x))
    }
    fn visit_i64<E>(self, x: i64) -> Result<Json, E> {
        Ok(if x >= 0 {
            Json::Uint(x as u64)
        } else {
            Json::Int(x)
        })
    }
    fn visit_f64<E>(self, x: f64) -> Result<Json, E> {
        Ok(Json::Float(x))
    }
    fn visit_str<E>(self, s: &str) -> Result<Json, E> {
        Ok(Json::Str(s.to_owned()))
    }
    fn visit_string<E>(self, s: String) -> Result<Json, E> {
        Ok(Json::Str(s))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Json, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        Ok(Json::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Json, A::Error> {
        let mut fields = Vec::new();
        while let Some((key, value)) = map.next_entry::<String, Json>()? {
            fields.push((key, value));
        }
        Ok(Json::Object(fields))
    }
}

impl<'de> Deserialize<'de> for Json {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(JsonVisitor)
    }
}
