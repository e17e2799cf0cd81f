//! The tiny expression language of `[derived]` rules.
//!
//! A rule such as `phi = "pi / complexity"` (thesis Fig. 4.18: φ = π/q) or
//! `offset = "0.1 * 8 / sides"` (D scaled with 1/n) gives a parameter as a function of others.
//! Grammar (usual precedence, left associative except `^`):
//!
//! ```text
//! expr    = term (("+" | "-") term)*
//! term    = unary (("*" | "×" | "/" | "÷") unary | implicit)*     implicit: `2pi`, `3(…)`, `2 sides`
//! unary   = ("-" | "−" | "+") unary | power
//! power   = atom ("^" unary)?
//! atom    = number | "pi" | "π" | name | "(" expr ")"
//! ```
//!
//! Numbers are decimal with an optional exponent (`1e-3`); names are parameters of the study
//! (their numeric value: angles in radians); a number directly followed by a name, `pi` or a
//! parenthesis multiplies it (`3pi/4`). Division by zero or any non-finite intermediate value
//! is an error of that case.

use std::collections::BTreeSet;
use std::fmt;

/// Why an expression could not be read or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExprError {
    /// A number the lexer cannot read.
    #[error("invalid number `{text}`")]
    InvalidNumber {
        /// The digits as written.
        text: String,
    },
    /// A character that is no part of an expression.
    #[error("unexpected character `{character}`")]
    UnexpectedCharacter {
        /// The character.
        character: char,
    },
    /// A token where another was expected.
    #[error("unexpected `{token}`")]
    UnexpectedToken {
        /// The token as written.
        token: String,
    },
    /// An opening parenthesis without its closing one.
    #[error("missing `)`")]
    MissingParenthesis,
    /// The expression ends where an operand is expected.
    #[error("unexpected end of the expression")]
    UnexpectedEnd,
    /// Nothing to read.
    #[error("empty expression")]
    Empty,
    /// A name the lookup does not know.
    #[error("unknown name `{name}`")]
    UnknownName {
        /// The name.
        name: String,
    },
    /// The lookup of a name failed (its message).
    #[error("{message}")]
    Lookup {
        /// The lookup's message.
        message: String,
    },
    /// A division by zero.
    #[error("division by zero")]
    DivisionByZero,
    /// The value overflowed or is NaN.
    #[error("the value is not finite")]
    NotFinite,
}

/// A parsed expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A literal.
    Number(f64),
    /// A parameter, by name.
    Name(String),
    /// −e.
    Neg(Box<Expr>),
    /// a op b.
    Binary(Op, Box<Expr>, Box<Expr>),
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// +
    Add,
    /// −
    Sub,
    /// ×
    Mul,
    /// ÷
    Div,
    /// ^
    Pow,
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Op(char),
    Open,
    Close,
}

impl fmt::Display for Token {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Number(x) => write!(f, "{x}"),
            Token::Name(n) => write!(f, "{n}"),
            Token::Op(c) => write!(f, "{c}"),
            Token::Open => write!(f, "("),
            Token::Close => write!(f, ")"),
        }
    }
}

fn lex(text: &str) -> Result<Vec<Token>, ExprError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // an exponent only when digits follow (`2e3`, `2e-3`); `2e` alone is 2·e (a name)
            if i < chars.len() && matches!(chars[i], 'e' | 'E') {
                let mut j = i + 1;
                if j < chars.len() && matches!(chars[j], '+' | '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    i = j;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let s: String = chars[start..i].iter().collect();
            let x: f64 = s
                .parse()
                .map_err(|_| ExprError::InvalidNumber { text: s.clone() })?;
            out.push(Token::Number(x));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Token::Name(chars[start..i].iter().collect()));
        } else {
            out.push(match c {
                '(' => Token::Open,
                ')' => Token::Close,
                '+' => Token::Op('+'),
                '-' | '−' => Token::Op('-'),
                '*' | '×' | '·' => Token::Op('*'),
                '/' | '÷' => Token::Op('/'),
                '^' => Token::Op('^'),
                other => return Err(ExprError::UnexpectedCharacter { character: other }),
            });
            i += 1;
        }
    }
    Ok(out)
}

struct Parser {
    tokens: Vec<Token>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    fn next(&mut self) -> Option<Token> {
        let t = self.tokens.get(self.at).cloned();
        self.at += 1;
        t
    }

    fn expr(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.term()?;
        while let Some(Token::Op(c @ ('+' | '-'))) = self.peek() {
            let op = if *c == '+' { Op::Add } else { Op::Sub };
            self.at += 1;
            left = Expr::Binary(op, Box::new(left), Box::new(self.term()?));
        }
        Ok(left)
    }

    fn term(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(Token::Op('*')) => Op::Mul,
                Some(Token::Op('/')) => Op::Div,
                // implicit product after a number: `3pi`, `2(…)`, `2 sides`
                Some(Token::Name(_) | Token::Open) if matches!(left, Expr::Number(_)) => {
                    left = Expr::Binary(Op::Mul, Box::new(left), Box::new(self.power()?));
                    continue;
                }
                _ => return Ok(left),
            };
            self.at += 1;
            left = Expr::Binary(op, Box::new(left), Box::new(self.unary()?));
        }
    }

    fn unary(&mut self) -> Result<Expr, ExprError> {
        match self.peek() {
            Some(Token::Op('-')) => {
                self.at += 1;
                Ok(Expr::Neg(Box::new(self.unary()?)))
            }
            Some(Token::Op('+')) => {
                self.at += 1;
                self.unary()
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<Expr, ExprError> {
        let base = self.atom()?;
        if let Some(Token::Op('^')) = self.peek() {
            self.at += 1;
            return Ok(Expr::Binary(
                Op::Pow,
                Box::new(base),
                Box::new(self.unary()?),
            ));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Expr, ExprError> {
        match self.next() {
            Some(Token::Number(x)) => Ok(Expr::Number(x)),
            Some(Token::Name(n)) if n == "pi" || n == "π" => {
                Ok(Expr::Number(std::f64::consts::PI))
            }
            Some(Token::Name(n)) => Ok(Expr::Name(n)),
            Some(Token::Open) => {
                let e = self.expr()?;
                match self.next() {
                    Some(Token::Close) => Ok(e),
                    _ => Err(ExprError::MissingParenthesis),
                }
            }
            Some(t) => Err(ExprError::UnexpectedToken {
                token: t.to_string(),
            }),
            None => Err(ExprError::UnexpectedEnd),
        }
    }
}

impl Expr {
    /// Parses an expression.
    ///
    /// ```
    /// use sweeps::expr::Expr;
    /// let e = Expr::parse("pi / complexity").unwrap();
    /// let phi = e.eval(&|name: &str| (name == "complexity").then_some(Ok(8.0))).unwrap();
    /// assert_eq!(phi, std::f64::consts::PI / 8.0);
    /// assert!(Expr::parse("2 * (sides").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        let tokens = lex(text)?;
        if tokens.is_empty() {
            return Err(ExprError::Empty);
        }
        let mut p = Parser { tokens, at: 0 };
        let e = p.expr()?;
        match p.peek() {
            None => Ok(e),
            Some(t) => Err(ExprError::UnexpectedToken {
                token: t.to_string(),
            }),
        }
    }

    /// The parameter names the expression uses.
    pub fn names(&self) -> BTreeSet<String> {
        let mut out = BTreeSet::new();
        self.collect_names(&mut out);
        out
    }

    fn collect_names(&self, out: &mut BTreeSet<String>) {
        match self {
            Expr::Number(_) => {}
            Expr::Name(n) => {
                out.insert(n.clone());
            }
            Expr::Neg(e) => e.collect_names(out),
            Expr::Binary(_, a, b) => {
                a.collect_names(out);
                b.collect_names(out);
            }
        }
    }

    /// Evaluates the expression; `lookup` gives a name's value (`None`: unknown name).
    pub fn eval(
        &self,
        lookup: &dyn Fn(&str) -> Option<Result<f64, String>>,
    ) -> Result<f64, ExprError> {
        let v = match self {
            Expr::Number(x) => *x,
            Expr::Name(n) => lookup(n)
                .ok_or_else(|| ExprError::UnknownName { name: n.clone() })?
                .map_err(|message| ExprError::Lookup { message })?,
            Expr::Neg(e) => -e.eval(lookup)?,
            Expr::Binary(op, a, b) => {
                let (a, b) = (a.eval(lookup)?, b.eval(lookup)?);
                match op {
                    Op::Add => a + b,
                    Op::Sub => a - b,
                    Op::Mul => a * b,
                    Op::Div if b == 0.0 => return Err(ExprError::DivisionByZero),
                    Op::Div => a / b,
                    Op::Pow => a.powf(b),
                }
            }
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(ExprError::NotFinite)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Expr;
    use std::f64::consts::PI;

    fn eval(text: &str) -> Result<f64, super::ExprError> {
        let vars = |n: &str| match n {
            "q" => Some(Ok(8.0)),
            "sides" => Some(Ok(16.0)),
            _ => None,
        };
        Expr::parse(text)?.eval(&vars)
    }

    #[test]
    fn precedence_and_forms() {
        assert_eq!(eval("1 + 2 * 3").unwrap(), 7.0);
        assert_eq!(eval("(1 + 2) * 3").unwrap(), 9.0);
        assert_eq!(eval("2 - 3 - 4").unwrap(), -5.0);
        assert_eq!(eval("2 ^ 3 ^ 2").unwrap(), 512.0);
        assert_eq!(eval("-2 ^ 2").unwrap(), -4.0);
        assert_eq!(eval("pi / q").unwrap(), PI / 8.0);
        assert_eq!(eval("3pi/4").unwrap(), 3.0 * PI / 4.0);
        assert_eq!(eval("0.1 × 8 ÷ sides").unwrap(), 0.1 * 8.0 / 16.0);
        assert_eq!(eval("1e-3 * sides").unwrap(), 1e-3 * 16.0);
        assert_eq!(eval("2(q + 1)").unwrap(), 18.0);
        assert_eq!(eval("π − 1").unwrap(), PI - 1.0);
    }

    #[test]
    fn errors_name_the_problem() {
        use super::ExprError as E;
        assert_eq!(eval("1 / (q - 8)"), Err(E::DivisionByZero));
        assert_eq!(eval("x + 1"), Err(E::UnknownName { name: "x".into() }));
        assert_eq!(eval("1 +"), Err(E::UnexpectedEnd));
        assert_eq!(eval("(1"), Err(E::MissingParenthesis));
        assert_eq!(
            eval("1 $ 2"),
            Err(E::UnexpectedCharacter { character: '$' })
        );
        assert_eq!(eval(""), Err(E::Empty));
        assert_eq!(eval("10 ^ 400"), Err(E::NotFinite));
        assert!(eval("x + 1").unwrap_err().to_string().contains("`x`"));
        let names = Expr::parse("pi / q + sides * q").unwrap().names();
        assert_eq!(names.into_iter().collect::<Vec<_>>(), ["q", "sides"]);
    }
}
