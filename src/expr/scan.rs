//! A scan of an expression's tokens that finds where it is wrong: exmex reports syntax
//! errors without a position. It accepts what exmex's float operators read (numbers with
//! an exponent, names, `+ - * / ^`, unary functions, `atan2(a, b)`, `min`, `max`).

/// The unary functions of exmex's float operators.
const UNARY: [&str; 26] = [
    "abs", "signum", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh",
    "acosh", "atanh", "floor", "round", "ceil", "trunc", "fract", "exp", "sqrt", "cbrt", "ln",
    "log2", "log10", "log",
];
/// Functions of two arguments, written `f(a, b)`.
const BINARY: [&str; 3] = ["atan2", "min", "max"];
/// Every function, for messages.
pub const FUNCTIONS: [&str; 29] = [
    "abs", "signum", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh",
    "acosh", "atanh", "floor", "round", "ceil", "trunc", "fract", "exp", "sqrt", "cbrt", "ln",
    "log2", "log10", "log", "atan2", "min", "max",
];

pub fn is_function(name: &str) -> bool {
    UNARY.contains(&name) || BINARY.contains(&name)
}

pub fn is_constant(name: &str) -> bool {
    matches!(name, "PI" | "π" | "E" | "e" | "TAU" | "τ")
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number,
    Name(String),
    Op(char),
    Open,
    Close,
    Comma,
    Bad(char),
}

/// (1-based character position, token).
fn tokens(text: &str) -> Vec<(usize, Token)> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = vec![];
    let mut i = 0;
    let digit = |c: Option<&char>| c.is_some_and(|c| c.is_ascii_digit());
    while i < chars.len() {
        let c = chars[i];
        let start = i + 1;
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        let tok = if c.is_ascii_digit() || (c == '.' && digit(chars.get(i + 1))) {
            while digit(chars.get(i)) {
                i += 1;
            }
            if chars.get(i) == Some(&'.') {
                i += 1;
                while digit(chars.get(i)) {
                    i += 1;
                }
            }
            // an exponent only when digits follow (else `e` is Euler's number or a name)
            if matches!(chars.get(i), Some('e' | 'E')) {
                let sign = usize::from(matches!(chars.get(i + 1), Some('+' | '-')));
                if digit(chars.get(i + 1 + sign)) {
                    i += 1 + sign;
                    while digit(chars.get(i)) {
                        i += 1;
                    }
                }
            }
            Token::Number
        } else if c.is_alphabetic() || c == '_' {
            let mut name = String::new();
            while let Some(&c) = chars.get(i).filter(|c| c.is_alphanumeric() || **c == '_') {
                name.push(c);
                i += 1;
            }
            Token::Name(name)
        } else {
            i += 1;
            match c {
                '+' | '-' | '*' | '/' | '^' => Token::Op(c),
                '(' => Token::Open,
                ')' => Token::Close,
                ',' => Token::Comma,
                _ => Token::Bad(c),
            }
        };
        out.push((start, tok));
    }
    out
}

/// The names of the expression (variables, functions, constants) with their positions.
pub fn names(text: &str) -> Vec<(usize, String)> {
    tokens(text)
        .into_iter()
        .filter_map(|(p, t)| match t {
            Token::Name(n) => Some((p, n)),
            _ => None,
        })
        .collect()
}

/// Whether a sign after this token is unary (an operand is expected there).
fn unary_context(t: &Token) -> bool {
    matches!(t, Token::Op(_) | Token::Open | Token::Comma)
}

/// The first syntax fault: (1-based character position, what).
pub fn check(text: &str) -> Result<(), (usize, String)> {
    let toks = tokens(text);
    // open parentheses: (position, function of two arguments?, commas seen)
    let mut open: Vec<(usize, Option<String>, usize)> = vec![];
    // whether an operand is expected next (at the start, after an operator, '(' or ',')
    let mut want_operand = true;
    let mut function: Option<(usize, String)> = None;
    // per parenthesis depth: the position of the unary minus right before the operand
    // being read at that depth, if any
    let mut negated: Vec<Option<usize>> = vec![None];
    // per parenthesis depth: the last binary operator
    let mut last_binary: Vec<Option<char>> = vec![None];
    for (k, (pos, tok)) in toks.iter().enumerate() {
        let pos = *pos;
        if let Some((at, f)) = function.take() {
            if *tok != Token::Open {
                return Err((
                    at,
                    format!("function '{f}' needs its argument in parentheses"),
                ));
            }
        }
        let starts_operand = want_operand
            && matches!(tok, Token::Number | Token::Name(_) | Token::Open)
            && !(k > 0 && matches!(&toks[k - 1].1, Token::Name(n) if is_function(n)));
        if starts_operand {
            let depth = open.len();
            negated.resize(depth + 1, None);
            negated[depth] = match k.checked_sub(1).map(|j| &toks[j]) {
                Some((p, Token::Op('-'))) if k == 1 || unary_context(&toks[k - 2].1) => Some(*p),
                _ => None,
            };
        }
        match tok {
            Token::Bad(c) => return Err((pos, format!("'{c}' is not allowed"))),
            Token::Number | Token::Name(_) | Token::Open if !want_operand => {
                let shown = match tok {
                    Token::Number => "a number".to_string(),
                    Token::Name(n) => format!("'{n}'"),
                    _ => "'('".to_string(),
                };
                return Err((pos, format!("{shown} follows a value without an operator")));
            }
            Token::Number => want_operand = false,
            Token::Name(n) if is_function(n) => {
                function = Some((pos, n.clone()));
            }
            Token::Name(_) => want_operand = false,
            Token::Open => {
                let f = match k.checked_sub(1).map(|j| &toks[j].1) {
                    Some(Token::Name(n)) if BINARY.contains(&n.as_str()) => Some(n.clone()),
                    _ => None,
                };
                open.push((pos, f, 0));
                last_binary.resize(open.len() + 1, None);
                last_binary[open.len()] = None;
            }
            Token::Op(c) if want_operand && !matches!(c, '+' | '-') => {
                let after_op = k > 0 && matches!(toks[k - 1].1, Token::Op(_));
                return Err((
                    pos,
                    if after_op {
                        format!("'{c}' follows an operator")
                    } else {
                        format!("'{c}' has no left operand")
                    },
                ));
            }
            Token::Op(c) => {
                // exmex reads a^b^c as (a^b)^c, against the usual a^(b^c)
                let depth = open.len();
                last_binary.resize(depth + 1, None);
                if *c == '^' && last_binary[depth] == Some('^') {
                    return Err((
                        pos,
                        "a power of a power is ambiguous: write (a^b)^c or a^(b^c)".into(),
                    ));
                }
                last_binary[depth] = Some(*c);
                // exmex binds a unary minus tighter than ^: -x^2 would be (-x)^2
                if *c == '^' {
                    if let Some(Some(minus)) = negated.get(open.len()) {
                        return Err((
                            *minus,
                            "a minus sign before a power is ambiguous: write -(x^2) for the \
                             negative of a square, or (-x)^2"
                                .into(),
                        ));
                    }
                }
                want_operand = true;
            }
            Token::Close | Token::Comma if want_operand => {
                let c = if *tok == Token::Close { ')' } else { ',' };
                return Err((pos, format!("'{c}' where a value is expected")));
            }
            Token::Close => {
                let Some((_, f, commas)) = open.pop() else {
                    return Err((pos, "')' closes nothing".into()));
                };
                if let Some(f) = f {
                    if commas != 1 {
                        return Err((pos, format!("'{f}' takes two arguments, written {f}(a, b)")));
                    }
                }
            }
            Token::Comma => match open.last_mut() {
                Some((_, Some(_), commas)) => {
                    *commas += 1;
                    last_binary.truncate(open.len());
                    last_binary.push(None);
                    want_operand = true;
                }
                _ => return Err((pos, "',' outside the arguments of atan2, min or max".into())),
            },
        }
    }
    if let Some((at, f)) = function {
        return Err((
            at,
            format!("function '{f}' needs its argument in parentheses"),
        ));
    }
    match toks.last() {
        None => return Err((0, "the expression is empty".into())),
        Some((p, Token::Op(_))) => return Err((*p, "the expression ends with an operator".into())),
        Some(_) if want_operand => {
            let end = text.chars().count();
            return Err((end, "the expression ends where a value is expected".into()));
        }
        _ => {}
    }
    if let Some((p, _, _)) = open.last() {
        return Err((*p, "'(' is not closed".into()));
    }
    Ok(())
}
