//! `Value`: what the case file gives for a load component, an imposed displacement or a
//! relation's right-hand side: a number (`dx = 0.001`) or an expression string
//! (`dx = "1e-3*x"`). TOML integers are numbers too.

use super::Expr;
use crate::error::{Error, Result};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Number(f64),
    Expr(String),
}

impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Number(v)
    }
}

impl std::ops::Mul<f64> for Value {
    type Output = Value;
    /// The value scaled by `k` (an expression becomes `(e)*(k)`).
    fn mul(self, k: f64) -> Value {
        match self {
            Value::Number(v) => Value::Number(v * k),
            Value::Expr(s) => Value::Expr(format!("({s})*({k:?})")),
        }
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Number(v) => write!(f, "{v}"),
            Value::Expr(s) => write!(f, "\"{s}\""),
        }
    }
}

impl Value {
    /// The number, if the value is one.
    pub fn number(&self) -> Option<f64> {
        match self {
            Value::Number(v) => Some(*v),
            Value::Expr(_) => None,
        }
    }

    /// Checks and compiles the value: a number must be finite, an expression may use the
    /// `allowed` variables. `what` names the entry and key in errors.
    pub fn compile(&self, allowed: &[&str], what: &str) -> Result<Compiled> {
        match self {
            Value::Number(v) if v.is_finite() => Ok(Compiled::Number(*v)),
            Value::Number(v) => Err(Error::model(format!(
                "{what} must be a finite number, got {v}"
            ))),
            Value::Expr(s) => Ok(Compiled::Expr(Expr::parse(s, allowed, what)?)),
        }
    }
}

/// A compiled `Value`.
#[derive(Clone, Debug)]
pub enum Compiled {
    Number(f64),
    Expr(Expr),
}

impl Compiled {
    #[inline]
    pub fn at(&self, x: [f64; 2], t: f64) -> f64 {
        match self {
            Compiled::Number(v) => *v,
            Compiled::Expr(e) => e.eval(x, t),
        }
    }

    pub fn uses_t(&self) -> bool {
        matches!(self, Compiled::Expr(e) if e.uses_t())
    }
}

impl Serialize for Value {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Value::Number(v) => s.serialize_f64(*v),
            Value::Expr(e) => s.serialize_str(e),
        }
    }
}

impl<'de> Deserialize<'de> for Value {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Value, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = Value;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or an expression string of x, y and t (e.g. \"1e-3*x\")")
            }
            fn visit_f64<E>(self, v: f64) -> std::result::Result<Value, E> {
                Ok(Value::Number(v))
            }
            fn visit_i64<E>(self, v: i64) -> std::result::Result<Value, E> {
                Ok(Value::Number(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> std::result::Result<Value, E> {
                Ok(Value::Number(v as f64))
            }
            fn visit_str<E>(self, v: &str) -> std::result::Result<Value, E> {
                Ok(Value::Expr(v.to_string()))
            }
        }
        d.deserialize_any(Visitor)
    }
}
