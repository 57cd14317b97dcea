//! The emptiness evidence (`empty/1`, FORMAT.md): a phase split tree
//! whose every leaf carries a reason the set misses it (a literal it
//! contradicts, or a factor of one constraint over another of one sign),
//! and the factor form those reasons read from a statement's constraints.
//! Shared by the `paving` and `parameter-atlas` claims.

use inari::Interval;

use super::encoding::BitReader;
use super::eval::Program;
use super::leaf::proved;
use super::tree::{iv, show_box, walk};
use super::Unreadable;

/// A token of the expression language, as written.
fn tokens(text: &str) -> Vec<&str> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let start = i;
        match b[i] {
            b' ' | b'\t' | b'\n' | b'\r' => {
                i += 1;
                continue;
            }
            c if c.is_ascii_digit() || c == b'.' => {
                while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                    i += 1;
                }
                // An exponent belongs to the number only with its digits.
                if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
                    let mut j = i + 1;
                    if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                        j += 1;
                    }
                    if j < b.len() && b[j].is_ascii_digit() {
                        while j < b.len() && b[j].is_ascii_digit() {
                            j += 1;
                        }
                        i = j;
                    }
                }
            }
            c if c.is_ascii_alphabetic() => {
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
            }
            _ => i += 1,
        }
        out.push(&text[start..i]);
    }
    out
}

/// `toks` without parentheses enclosing all of it (repeatedly).
fn strip<'a, 'b>(mut toks: &'a [&'b str]) -> &'a [&'b str] {
    while toks.len() >= 2 && toks[0] == "(" && toks[toks.len() - 1] == ")" {
        let mut depth = 0i32;
        let closes_at_end = toks.iter().enumerate().all(|(k, &t)| {
            depth += i32::from(t == "(") - i32::from(t == ")");
            depth > 0 || k == toks.len() - 1
        });
        if !closes_at_end {
            break;
        }
        toks = &toks[1..toks.len() - 1];
    }
    toks
}

/// The factor of `product` over `base` (FORMAT.md, "the factor form"): with
/// enclosing parentheses removed, `product` is `L * R` or `L / R` at its last
/// `*` or `/` outside parentheses, with no `+` or binary `-` there, and `L`
/// (or, for `*` only, `R`) is the same token sequence as `base`. Returns the
/// other operand's text. Two equal token sequences are the same function:
/// the factor `1`.
pub(crate) fn factor_text(product: &str, base: &str) -> Option<String> {
    let all = tokens(product);
    let toks = strip(&all);
    let base_toks = tokens(base);
    let base = strip(&base_toks);
    if toks == base {
        return Some("1".into());
    }
    let mut depth = 0i32;
    let mut split = None;
    for (k, &t) in toks.iter().enumerate() {
        match t {
            "(" => depth += 1,
            ")" => depth -= 1,
            "+" if depth == 0 => return None,
            // Binary minus: after an operand (a number, a name or `)`).
            "-" if depth == 0
                && k > 0
                && toks[k - 1]
                    .bytes()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'.' || c == b')') =>
            {
                return None
            }
            "*" | "/" if depth == 0 => split = Some(k),
            _ => {}
        }
    }
    let k = split?;
    let (l, r) = (strip(&toks[..k]), strip(&toks[k + 1..]));
    let f = if l == base {
        &toks[k + 1..]
    } else if toks[k] == "*" && r == base {
        &toks[..k]
    } else {
        return None;
    };
    Some(f.join(" "))
}

/// `factor[j][i]` of a statement's constraints (FORMAT.md, "the factor
/// form"), each factor compiled into `prog`.
pub(crate) fn factor_table(
    prog: &mut Program,
    names: &[String],
    texts: &[&str],
) -> Result<Vec<Vec<Option<u32>>>, Unreadable> {
    let n = texts.len();
    let mut factor = vec![vec![None; n]; n];
    for (j, row) in factor.iter_mut().enumerate() {
        for (i, slot) in row.iter_mut().enumerate() {
            if i == j {
                continue;
            }
            if let Some(f) = factor_text(texts[j], texts[i]) {
                *slot = Some(
                    prog.compile(&f)
                        .map_err(|e| format!("factor of constraint {}: {e}", names[j]))?,
                );
            }
        }
    }
    Ok(factor)
}

/// What an emptiness reason is checked against: a statement's constraints
/// (their names, values and factor forms) and the phase box its trees
/// start from.
pub(crate) struct Reasons<'a> {
    pub prog: &'a Program,
    pub names: &'a [String],
    pub roots: &'a [u32],
    pub factor: &'a [Vec<Option<u32>>],
    pub phase_box: [f64; 4],
}

/// The set's literal for constraint `c`, if it has one.
fn literal(literals: &[(usize, bool)], c: usize) -> Option<bool> {
    literals
        .iter()
        .find(|&&(k, _)| k == c)
        .map(|&(_, want_in)| want_in)
}

/// Why the set misses one phase leaf `t × w`; `None` when the reason holds.
fn reason_fails(
    st: &Reasons,
    literals: &[(usize, bool)],
    bits: &mut BitReader,
    t: Interval,
    w: Interval,
) -> Result<Option<String>, ()> {
    let nc = st.roots.len();
    if !bits.bit().ok_or(())? {
        let c = bits.bits(2).ok_or(())? as usize;
        if c >= nc {
            return Ok(Some(format!("literal reason names constraint {}", c + 1)));
        }
        let Some(want_in) = literal(literals, c) else {
            return Ok(Some(format!(
                "literal reason: the set has no literal of {}",
                st.names[c]
            )));
        };
        // The literal fails when the opposite label is proved.
        if proved(st.prog, st.roots[c], t, w, !want_in) {
            return Ok(None);
        }
        return Ok(Some(format!(
            "literal reason: {} is not proved {}",
            st.names[c],
            if want_in { "out" } else { "in" }
        )));
    }
    let j = bits.bits(2).ok_or(())? as usize;
    let i = bits.bits(2).ok_or(())? as usize;
    let positive = bits.bit().ok_or(())?;
    if j >= nc || i >= nc {
        return Ok(Some(format!(
            "factor reason names constraints {} and {}",
            j + 1,
            i + 1
        )));
    }
    let Some(f) = st.factor[j][i] else {
        return Ok(Some(format!(
            "factor reason: {} is not {} times or divided by a factor",
            st.names[j], st.names[i]
        )));
    };
    let contradicts = match (literal(literals, j), literal(literals, i)) {
        (Some(a), Some(b)) if positive => a != b,
        (Some(true), Some(true)) => true,
        _ => false,
    };
    if !contradicts {
        return Ok(Some(format!(
            "factor reason: a {} factor does not contradict the set's literals of {} and {}",
            if positive { "positive" } else { "negative" },
            st.names[j],
            st.names[i]
        )));
    }
    // Positive: F > 0, the label out of F; negative: F < 0, the label in.
    if proved(st.prog, f, t, w, !positive) {
        return Ok(None);
    }
    Ok(Some(format!(
        "factor reason: the factor of {} over {} is not proved {}",
        st.names[j],
        st.names[i],
        if positive { "positive" } else { "negative" }
    )))
}

/// An emptiness tree (`empty/1`) of the set with these literals: replayed
/// from the phase box, every leaf's reason checked.
pub(crate) fn empty_tree(
    st: &Reasons,
    literals: &[(usize, bool)],
    nodes_claimed: u64,
    body: &[u8],
    what: &str,
    checked: &mut u64,
) -> Result<(), String> {
    let mut bits = BitReader::new(body);
    let mut leaves = 0u64;
    let walked = walk(&mut bits, st.phase_box, nodes_claimed, |b, bits, node| {
        leaves += 1;
        let (t, w) = (iv(b[0], b[1]), iv(b[2], b[3]));
        match reason_fails(st, literals, bits, t, w) {
            Err(()) => return Err(format!("the bit string ends inside node {node}")),
            Ok(Some(why)) => return Err(format!("leaf {leaves} {}: {why}", show_box(&b))),
            Ok(None) => {}
        }
        *checked += 1;
        Ok(())
    })
    .map_err(|e| format!("{what}: {e}"))?;
    if walked.nodes != nodes_claimed {
        return Err(format!(
            "{what}: the tree has {} nodes, claimed {nodes_claimed}",
            walked.nodes
        ));
    }
    Ok(())
}
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_factor_form_is_read_from_the_tokens() {
        // Division and multiplication, either side of `*`, parentheses.
        assert_eq!(factor_text("U/V", "U").as_deref(), Some("V"));
        assert_eq!(factor_text("U * V", "U").as_deref(), Some("V"));
        assert_eq!(factor_text("V*U", "U").as_deref(), Some("V"));
        assert_eq!(
            factor_text("((U)/(1 + t))", "(U)").as_deref(),
            Some("( 1 + t )")
        );
        assert_eq!(
            factor_text("(w^2 - g)/cos(t)", "w^2-g").as_deref(),
            Some("cos ( t )")
        );
        assert_eq!(factor_text("-U/V", "-U").as_deref(), Some("V"));
        assert_eq!(factor_text("U*-V", "U").as_deref(), Some("- V"));
        // Not of the form: a sum, a binary minus, the denominator, another
        // product, or the wrong base.
        assert_eq!(factor_text("U/V + 0", "U"), None);
        assert_eq!(factor_text("U/V - 1e-5", "U"), None);
        assert_eq!(factor_text("V/U", "U"), None);
        assert_eq!(factor_text("U*V*W", "U"), None);
        assert_eq!(factor_text("U/V", "u"), None);
        // The same tokens are the same function: the factor 1.
        assert_eq!(factor_text("U", "U").as_deref(), Some("1"));
        assert_eq!(factor_text("(a*w - b)", "a * w-b").as_deref(), Some("1"));
        assert_eq!(factor_text("a*w - b", "a*w - c"), None);
        assert_eq!(factor_text("(U)*(V)/(W)", "U"), None);
        // A number's exponent sign is no operator: 2e-3*U is 2e-3 times U.
        assert_eq!(factor_text("2e-3*U", "U").as_deref(), Some("2e-3"));
        assert_eq!(factor_text("(a)-(b)*U", "U"), None);
    }
}
