//! What a proof of a scene file states: the author's definitions and regions
//! as written in the file, in the proof format's names.
//!
//! The text is the file's, token for token: the variables are renamed by one
//! rule (`theta` → `t`, `theta_dot` → `w`, the names `proofs/FORMAT.md` gives
//! them; a scene file may not use `t` or `w` itself), runs of white space
//! become one space, and nothing else changes. A parameter or literal keeps
//! its name or digits whatever its value, so two parameters that are both
//! `2` stay `a` and `b`. Each region is its normal form `{expr < 0}`
//! ([`crate::scene::file`]: `lhs < rhs` is `(lhs) - (rhs)`, a zero side
//! dropped). The checker evaluates that text by FORMAT.md's rules, so the
//! labels a proof states are first confirmed on it ([`super::confirm`]).

use crate::scene::FileScene;

/// The name a proof file gives a scene file's variable, if it is one.
fn proof_name(name: &str) -> Option<&'static str> {
    match name {
        "theta" => Some("t"),
        "theta_dot" => Some("w"),
        _ => None,
    }
}

/// A token of an expression, as far as renaming needs: a name, a number, a
/// run of white space, or one other character.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Piece<'a> {
    Name(&'a str),
    Other(&'a str),
    Space,
}

/// Splits text of the expression language (FORMAT.md "Expressions") into
/// names, numbers (kept whole, so the `e` of `1e5` is never a name) and the
/// rest. The text has parsed as a scene-file expression already.
fn pieces(text: &str) -> Vec<Piece<'_>> {
    let b = text.as_bytes();
    let digits = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let start = i;
        match b[i] {
            c if c.is_ascii_whitespace() => {
                while i < b.len() && b[i].is_ascii_whitespace() {
                    i += 1;
                }
                out.push(Piece::Space);
            }
            c if c.is_ascii_alphabetic() => {
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push(Piece::Name(&text[start..i]));
            }
            b'0'..=b'9' | b'.' => {
                i = digits(i);
                if b.get(i) == Some(&b'.') {
                    i = digits(i + 1);
                }
                if matches!(b.get(i), Some(b'e' | b'E')) {
                    let mut j = i + 1;
                    if matches!(b.get(j), Some(b'+' | b'-')) {
                        j += 1;
                    }
                    let k = digits(j);
                    if k > j {
                        i = k;
                    }
                }
                out.push(Piece::Other(&text[start..i]));
            }
            _ => {
                let len = text[i..].chars().next().map_or(1, char::len_utf8);
                i += len;
                out.push(Piece::Other(&text[start..i]));
            }
        }
    }
    out
}

/// `text` with the variables in the proof format's names and white space
/// normalised (one space for a run, none at the ends).
pub fn in_proof_names(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for p in pieces(text.trim()) {
        match p {
            Piece::Name(n) => out.push_str(proof_name(n).unwrap_or(n)),
            Piece::Other(s) => out.push_str(s),
            Piece::Space => out.push(' '),
        }
    }
    out
}

/// The names an expression uses (functions and variables included).
fn names_in(text: &str) -> impl Iterator<Item = &str> {
    pieces(text).into_iter().filter_map(|p| match p {
        Piece::Name(n) => Some(n),
        _ => None,
    })
}

/// A scene file's statement in the proof format: the definitions the two
/// regions use (each after those it names, otherwise in file order) and the
/// two regions as `{expr < 0}`.
pub struct FileStatement {
    pub definitions: Vec<(String, String)>,
    pub omega: String,
    pub omega0: String,
}

/// The statement of `f`'s regions as the author wrote them.
pub fn file_statement(f: &FileScene) -> FileStatement {
    FileStatement {
        definitions: definitions_for(f, f.regions.iter().map(|r| r.expr.as_str())),
        omega: in_proof_names(&f.regions[0].expr),
        omega0: in_proof_names(&f.regions[1].expr),
    }
}

/// The definitions of `f` that `exprs` use, directly or through others,
/// each placed after every definition it names, in the proof's names.
pub fn definitions_for<'a>(
    f: &FileScene,
    exprs: impl IntoIterator<Item = &'a str>,
) -> Vec<(String, String)> {
    let defs = &f.definitions;
    let index = |n: &str| defs.iter().position(|(d, _)| d == n);
    // Depth-first from the expressions. The file's definitions have no
    // cycle (the scene compiler refuses one), and `placed` bounds the walk
    // regardless.
    let mut placed = vec![false; defs.len()];
    let mut order = Vec::new();
    let mut stack: Vec<(usize, bool)> = Vec::new();
    for e in exprs {
        for n in names_in(e) {
            if let Some(i) = index(n) {
                stack.push((i, false));
            }
        }
        while let Some((i, expanded)) = stack.pop() {
            if placed[i] {
                continue;
            }
            if expanded {
                placed[i] = true;
                order.push(i);
                continue;
            }
            stack.push((i, true));
            let uses: Vec<usize> = names_in(&defs[i].1)
                .filter_map(index)
                .filter(|&j| !placed[j] && j != i)
                .collect();
            stack.extend(uses.into_iter().rev().map(|j| (j, false)));
        }
    }
    order
        .into_iter()
        .map(|i| (defs[i].0.clone(), in_proof_names(&defs[i].1)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variables_are_renamed_and_nothing_else() {
        assert_eq!(
            in_proof_names("l*sin(theta)*theta_dot^2 - g"),
            "l*sin(t)*w^2 - g"
        );
        // Names that contain the variables' names, numbers with exponents
        // (the `e` is no name) and spacing.
        assert_eq!(
            in_proof_names("  theta_dot2 +\n\ttheta1*1e-3 + 2.5E+2*thetax  "),
            "theta_dot2 + theta1*1e-3 + 2.5E+2*thetax"
        );
        assert_eq!(in_proof_names("(theta)-(theta_dot)"), "(t)-(w)");
        assert_eq!(in_proof_names("min(theta,2.)"), "min(t,2.)");
    }

    #[test]
    fn definitions_follow_what_they_use() {
        let text = "name = \"x\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
                    [parameters]\na = \"2\"\n[definitions]\nA = \"B + theta\"\nB = \"a*C\"\n\
                    C = \"cos(theta)\"\nunused = \"C*C\"\n[regions]\nomega = \"A*theta_dot < 1\"\n";
        let f = FileScene::parse(text, &[]).unwrap();
        let s = file_statement(&f);
        let names: Vec<&str> = s.definitions.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["C", "B", "A"]);
        assert_eq!(s.definitions[0].1, "cos(t)");
        assert_eq!(s.omega, "(A*w) - (1)");
        assert_eq!(s.omega0, s.omega);
    }
}
