//! Typed access to the JSON of a proof file; every failure is [`Unreadable`].

use serde_json::{Map, Value};
use std::collections::HashSet;

use super::Unreadable;

pub type Obj = Map<String, Value>;

pub fn as_obj<'a>(v: &'a Value, what: &str) -> Result<&'a Obj, Unreadable> {
    v.as_object()
        .ok_or_else(|| Unreadable(format!("{what} must be a JSON object")))
}

fn get<'a>(o: &'a Obj, key: &str) -> Result<&'a Value, Unreadable> {
    o.get(key)
        .ok_or_else(|| Unreadable(format!("missing key {key:?}")))
}

pub fn str_of<'a>(o: &'a Obj, key: &str) -> Result<&'a str, Unreadable> {
    get(o, key)?
        .as_str()
        .ok_or_else(|| Unreadable(format!("{key:?} must be a string")))
}

/// An optional string: absent is `None`, any other type is unreadable.
pub fn opt_str<'a>(o: &'a Obj, key: &str) -> Result<Option<&'a str>, Unreadable> {
    match o.get(key) {
        None => Ok(None),
        Some(v) => v
            .as_str()
            .map(Some)
            .ok_or_else(|| Unreadable(format!("{key:?} must be a string"))),
    }
}

pub fn obj_of<'a>(o: &'a Obj, key: &str) -> Result<&'a Obj, Unreadable> {
    as_obj(get(o, key)?, key)
}

pub fn arr_of<'a>(o: &'a Obj, key: &str) -> Result<&'a Vec<Value>, Unreadable> {
    get(o, key)?
        .as_array()
        .ok_or_else(|| Unreadable(format!("{key:?} must be an array")))
}

pub fn u64_of(o: &Obj, key: &str) -> Result<u64, Unreadable> {
    get(o, key)?
        .as_u64()
        .ok_or_else(|| Unreadable(format!("{key:?} must be a non-negative integer")))
}

pub fn bool_of(o: &Obj, key: &str) -> Result<bool, Unreadable> {
    get(o, key)?
        .as_bool()
        .ok_or_else(|| Unreadable(format!("{key:?} must be true or false")))
}

/// An array of exactly two strings.
pub fn pair_of<'a>(v: &'a Value, what: &str) -> Result<(&'a str, &'a str), Unreadable> {
    match v.as_array().map(|a| a.as_slice()) {
        Some([Value::String(a), Value::String(b)]) => Ok((a, b)),
        _ => Err(Unreadable(format!(
            "{what} must be an array of two strings"
        ))),
    }
}

/// `parameters` (name → decimal text) and `definitions` (`[name, expr]`
/// pairs) of a statement, in file order.
pub type Decls = (Vec<(String, String)>, Vec<(String, String)>);

pub fn decls(st: &Obj) -> Result<Decls, Unreadable> {
    let mut params = Vec::new();
    for (k, v) in obj_of(st, "parameters")? {
        // A string is one value; two strings [lo, hi] are a parameter box.
        let text = match v {
            Value::String(t) if !t.starts_with('[') => t.clone(),
            Value::Array(_) => {
                let (a, b) = pair_of(v, &format!("parameter {k:?}"))?;
                format!("[{a},{b}]")
            }
            _ => {
                return Err(Unreadable(format!(
                    "parameter {k:?} must be a decimal string or [lo, hi]"
                )))
            }
        };
        params.push((k.clone(), text));
    }
    let mut defs = Vec::new();
    for (i, d) in arr_of(st, "definitions")?.iter().enumerate() {
        let (n, e) = pair_of(d, &format!("definition {}", i + 1))?;
        defs.push((n.to_string(), e.to_string()));
    }
    Ok((params, defs))
}

/// Rejects a JSON text (already known to be valid) in which some object has
/// the same key twice: a reader would see one value, the checker another.
/// An upper bound on the number of JSON values in `text`: one more than the
/// `{`, `[` and `,` outside strings. Read before the text is parsed.
pub fn count_values(text: &str) -> usize {
    let mut n = 1;
    let mut in_string = false;
    let mut escaped = false;
    for &b in text.as_bytes() {
        if in_string {
            match (escaped, b) {
                (true, _) => escaped = false,
                (false, b'\\') => escaped = true,
                (false, b'"') => in_string = false,
                _ => {}
            }
        } else {
            match b {
                b'"' => in_string = true,
                b'{' | b'[' | b',' => n += 1,
                _ => {}
            }
        }
    }
    n
}

pub fn reject_duplicate_keys(text: &str) -> Result<(), Unreadable> {
    // One frame per open object (`Some`) or array (`None`); the flag says the
    // next string in that object is a key.
    let mut stack: Vec<Option<(HashSet<String>, bool)>> = Vec::new();
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'{' => stack.push(Some((HashSet::new(), true))),
            b'[' => stack.push(None),
            b'}' | b']' => {
                stack.pop();
            }
            b',' => {
                if let Some(Some((_, want_key))) = stack.last_mut() {
                    *want_key = true;
                }
            }
            b'"' => {
                let start = i;
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    if b[i] == b'\\' {
                        i += 1;
                    }
                    i += 1;
                }
                let raw = text.get(start..=i.min(b.len() - 1)).unwrap_or("");
                if let Some(Some((keys, want_key))) = stack.last_mut() {
                    if *want_key {
                        *want_key = false;
                        let key: String = serde_json::from_str(raw)
                            .map_err(|e| Unreadable(format!("bad key: {e}")))?;
                        if !keys.insert(key.clone()) {
                            return Err(Unreadable(format!("duplicate key {key:?}")));
                        }
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    Ok(())
}
