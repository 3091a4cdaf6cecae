//! An f64 written as a JSON number, or as the string "inf" when it is +infinity (JSON
//! has no infinity): the serde `with` module of every such field (case files, reports,
//! expectations, stability rows).

use serde::{Deserialize, Deserializer, Serializer};

pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if *v == f64::INFINITY {
        s.serialize_str("inf")
    } else {
        s.serialize_f64(*v)
    }
}

#[derive(Deserialize)]
#[serde(untagged)]
enum NumOrStr {
    Num(f64),
    Str(String),
}

pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    match NumOrStr::deserialize(d)? {
        NumOrStr::Num(v) => Ok(v),
        NumOrStr::Str(s) if s == "inf" => Ok(f64::INFINITY),
        NumOrStr::Str(s) => Err(serde::de::Error::custom(format!(
            "expected a number or \"inf\", found {}",
            crate::io::quote::quote(&s)
        ))),
    }
}
