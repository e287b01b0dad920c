//! The arithmetic of `#calc "…"` and `#eval{ … }`, evaluated when the file is read.
//!
//! OpenFOAM compiles `#calc` as C++ and evaluates `#eval` with its expression parser. fsim
//! evaluates the subset that case files use to size a block: numbers, `+ - * / %`,
//! parentheses, the usual functions (`sin`, `sqrt`, `pow`, `degToRad`, …) and `pi`. The
//! parser has already replaced each `$var` by its number. Anything else leaves the directive
//! unevaluated, and a typed accessor then says that fsim does not evaluate it.

use nom::number::complete::recognize_float;

/// A result: integer when every operand was an integer (C++ arithmetic for `#calc`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Number {
    Int(i64),
    Real(f64),
}

impl Number {
    fn real(self) -> f64 {
        match self {
            Number::Int(n) => n as f64,
            Number::Real(x) => x,
        }
    }
}

/// Evaluates `text`. With `integer_division` (C++ `#calc`), `7/2` is 3; otherwise (`#eval`)
/// every division is real.
pub fn evaluate(text: &str, integer_division: bool) -> Option<Number> {
    let mut p = Expr {
        rest: text,
        integer_division,
        depth: 0,
    };
    let value = p.sum()?;
    p.blank();
    p.rest.is_empty().then_some(value)
}

struct Expr<'a> {
    rest: &'a str,
    integer_division: bool,
    depth: usize,
}

impl<'a> Expr<'a> {
    fn blank(&mut self) {
        self.rest = self.rest.trim_start();
    }

    fn eat(&mut self, c: char) -> bool {
        self.blank();
        match self.rest.strip_prefix(c) {
            Some(r) => {
                self.rest = r;
                true
            }
            None => false,
        }
    }

    fn sum(&mut self) -> Option<Number> {
        let mut acc = self.product()?;
        loop {
            if self.eat('+') {
                acc = arith(acc, self.product()?, '+', self.integer_division)?;
            } else if self.eat('-') {
                acc = arith(acc, self.product()?, '-', self.integer_division)?;
            } else {
                return Some(acc);
            }
        }
    }

    fn product(&mut self) -> Option<Number> {
        let mut acc = self.unary()?;
        loop {
            let op = ['*', '/', '%'].into_iter().find(|&c| self.eat(c));
            match op {
                Some(op) => acc = arith(acc, self.unary()?, op, self.integer_division)?,
                None => return Some(acc),
            }
        }
    }

    fn unary(&mut self) -> Option<Number> {
        self.depth += 1;
        // Bounded recursion: `------…1` or `((((…` cannot overflow the stack.
        if self.depth > 200 {
            return None;
        }
        let v = if self.eat('-') {
            match self.unary()? {
                Number::Int(n) => Number::Int(n.checked_neg()?),
                Number::Real(x) => Number::Real(-x),
            }
        } else if self.eat('+') {
            self.unary()?
        } else {
            self.primary()?
        };
        self.depth -= 1;
        Some(v)
    }

    fn primary(&mut self) -> Option<Number> {
        self.blank();
        if self.eat('(') {
            let v = self.sum()?;
            return self.eat(')').then_some(v);
        }
        if self
            .rest
            .starts_with(|c: char| c.is_ascii_digit() || c == '.')
        {
            let (rest, text) = recognize_float::<_, nom::error::Error<&str>>(self.rest).ok()?;
            self.rest = rest;
            return if text.contains(['.', 'e', 'E']) {
                text.parse().ok().map(Number::Real)
            } else {
                text.parse().ok().map(Number::Int)
            };
        }
        let len = self
            .rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'))
            .unwrap_or(self.rest.len());
        if len == 0 {
            return None;
        }
        let name = &self.rest[..len];
        self.rest = &self.rest[len..];
        let name = name.rsplit("::").next().unwrap_or(name);
        let mut args = Vec::new();
        let call = self.eat('(');
        if call && !self.eat(')') {
            loop {
                args.push(self.sum()?.real());
                if self.eat(')') {
                    break;
                }
                if !self.eat(',') {
                    return None;
                }
            }
        }
        function(name, call, &args).map(Number::Real)
    }
}

fn arith(a: Number, b: Number, op: char, integer_division: bool) -> Option<Number> {
    match (a, b) {
        (Number::Int(x), Number::Int(y)) if op != '/' || integer_division => {
            Some(Number::Int(match op {
                '+' => x.checked_add(y)?,
                '-' => x.checked_sub(y)?,
                '*' => x.checked_mul(y)?,
                '/' => x.checked_div(y)?,
                _ => x.checked_rem(y)?,
            }))
        }
        _ => {
            let (x, y) = (a.real(), b.real());
            let v = match op {
                '+' => x + y,
                '-' => x - y,
                '*' => x * y,
                '/' => x / y,
                _ => x % y,
            };
            v.is_finite().then_some(Number::Real(v))
        }
    }
}

/// Constants (`pi`, `pi()`) and functions of real arguments.
fn function(name: &str, call: bool, a: &[f64]) -> Option<f64> {
    use std::f64::consts::PI;
    let v = match (name, a) {
        ("pi" | "M_PI", []) => PI,
        (_, _) if !call => return None,
        ("degToRad", [x]) => x * PI / 180.0,
        ("radToDeg", [x]) => x * 180.0 / PI,
        ("sin", [x]) => x.sin(),
        ("cos", [x]) => x.cos(),
        ("tan", [x]) => x.tan(),
        ("asin", [x]) => x.asin(),
        ("acos", [x]) => x.acos(),
        ("atan", [x]) => x.atan(),
        ("atan2", [y, x]) => y.atan2(*x),
        ("sqrt", [x]) => x.sqrt(),
        ("cbrt", [x]) => x.cbrt(),
        ("pow", [x, y]) => x.powf(*y),
        ("sqr", [x]) => x * x,
        ("exp", [x]) => x.exp(),
        ("log", [x]) => x.ln(),
        ("log10", [x]) => x.log10(),
        ("abs" | "mag" | "fabs", [x]) => x.abs(),
        ("min", [x, y]) => x.min(*y),
        ("max", [x, y]) => x.max(*y),
        ("floor", [x]) => x.floor(),
        ("ceil", [x]) => x.ceil(),
        ("round", [x]) => x.round(),
        _ => return None,
    };
    v.is_finite().then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn real(text: &str) -> f64 {
        match evaluate(text, false) {
            Some(n) => n.real(),
            None => panic!("{text} did not evaluate"),
        }
    }

    #[test]
    fn arithmetic_and_precedence() {
        assert_eq!(evaluate("2*3+4", true), Some(Number::Int(10)));
        assert_eq!(evaluate("2*(3+4)", true), Some(Number::Int(14)));
        assert_eq!(evaluate("-2 - -3", true), Some(Number::Int(1)));
        // C++ `#calc` divides integers as integers; `#eval` does not.
        assert_eq!(evaluate("7/2", true), Some(Number::Int(3)));
        assert_eq!(evaluate("7/2", false), Some(Number::Real(3.5)));
        assert_eq!(evaluate("7 % 4", true), Some(Number::Int(3)));
        assert_eq!(evaluate("0.5*4", true), Some(Number::Real(2.0)));
        assert_eq!(evaluate("1e-3*2", true), Some(Number::Real(2e-3)));
    }

    #[test]
    fn functions_and_constants() {
        assert!((real("20*pi()") - 20.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!((real("2*sin(degToRad(30))") - 1.0).abs() < 1e-12);
        assert!((real("Foam::sqrt(16) + pow(2, 3)") - 12.0).abs() < 1e-12);
        assert!((real("constant::mathematical::pi/2") - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn anything_else_is_left_alone() {
        for text in [
            "",
            "1 +",
            "x*2",
            "vector(1, 2, 3)",
            "1/0",
            "2 3",
            "sin(1, 2)",
            "(1",
        ] {
            assert_eq!(evaluate(text, true), None, "{text}");
        }
        assert_eq!(evaluate(&"-".repeat(10_000), true), None);
        assert_eq!(evaluate("9223372036854775807 + 1", true), None);
    }
}
