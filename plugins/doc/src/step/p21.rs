//! A small reader of ISO 10303-21 exchange structures (STEP "Part 21"
//! text): the header section's records and the data section's entity
//! instances, simple (`#1 = NAME(…);`) and complex (`#1 = (A(…) B(…));`),
//! each with the line it starts on, so that every later error can name
//! the line and the entity.
//!
//! Hostile input is refused with an error, never a panic: lists nest at
//! most [`MAX_DEPTH`] deep and hold at most [`MAX_LIST`] values, a file
//! holds at most [`MAX_ENTITIES`] instances, an id appears once, numbers
//! are finite. [`Exchange::check_acyclic`] refuses reference cycles.

use std::collections::HashMap;

/// Nesting of parenthesised lists an instance may have at most.
pub const MAX_DEPTH: usize = 16;
/// Values one list may hold at most.
pub const MAX_LIST: usize = 4_000_000;
/// Entity instances a file may hold at most.
pub const MAX_ENTITIES: usize = 4_000_000;

/// One parameter of a record.
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    /// An integer.
    Int(i64),
    /// A real number.
    Real(f64),
    /// A string, its escapes decoded.
    Str(String),
    /// An enumeration value, without its dots (`.T.` is `T`).
    Enum(String),
    /// A reference to an entity instance (`#12`).
    Ref(u64),
    /// A list.
    List(Vec<Param>),
    /// `$`: no value.
    Unset,
    /// `*`: a value derived by the schema.
    Derived,
    /// A typed value, `LENGTH_MEASURE(1.E-07)`.
    Typed(String, Box<Param>),
    /// A binary value, as its hex text.
    Binary(String),
}

/// A record: an entity type name and its parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The type name, upper case.
    pub name: String,
    /// Its parameters.
    pub params: Vec<Param>,
}

/// An entity instance of the data section.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The line (from 1) where `#id` stands.
    pub line: u32,
    /// One record for a simple instance; the partial records of a complex
    /// one, in the file's order.
    pub records: Vec<Record>,
    /// Written as a complex instance `( A() B() )`.
    pub complex: bool,
}

/// A parsed exchange structure.
#[derive(Clone, Debug, Default)]
pub struct Exchange {
    /// The header section's records (FILE_DESCRIPTION, FILE_NAME, FILE_SCHEMA).
    pub header: Vec<Record>,
    /// Every instance by id.
    pub instances: HashMap<u64, Instance>,
    /// Ids in the order of the file.
    pub order: Vec<u64>,
}

/// A syntax or structure error, with the line and, where known, the instance.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    /// The line, from 1.
    pub line: u32,
    /// The instance being read, when there is one.
    pub entity: Option<u64>,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.entity {
            Some(id) => write!(f, "line {}, #{id}: {}", self.line, self.message),
            None => write!(f, "line {}: {}", self.line, self.message),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Keyword(String),
    Int(i64),
    Real(f64),
    Str(String),
    Enum(String),
    Ref(u64),
    Binary(String),
    Open,
    Close,
    Comma,
    Equals,
    Semicolon,
    Dollar,
    Star,
    End,
}

struct Lexer<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u32,
}

impl<'a> Lexer<'a> {
    fn err(&self, message: impl Into<String>) -> SyntaxError {
        SyntaxError {
            line: self.line,
            entity: None,
            message: message.into(),
        }
    }

    fn skip_space(&mut self) -> Result<(), SyntaxError> {
        loop {
            match self.bytes.get(self.pos) {
                Some(b'\n') => {
                    self.line += 1;
                    self.pos += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.pos += 1,
                Some(b'/') if self.bytes.get(self.pos + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.pos += 2;
                    loop {
                        match self.bytes.get(self.pos) {
                            None => {
                                return Err(SyntaxError {
                                    line: start,
                                    entity: None,
                                    message: "a comment that is never closed (*/)".into(),
                                });
                            }
                            Some(b'*') if self.bytes.get(self.pos + 1) == Some(&b'/') => {
                                self.pos += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.pos += 1;
                            }
                            Some(_) => self.pos += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn next(&mut self) -> Result<Token, SyntaxError> {
        self.skip_space()?;
        let Some(&c) = self.bytes.get(self.pos) else {
            return Ok(Token::End);
        };
        let single = |t: Token, l: &mut Self| {
            l.pos += 1;
            Ok(t)
        };
        match c {
            b'(' => single(Token::Open, self),
            b')' => single(Token::Close, self),
            b',' => single(Token::Comma, self),
            b'=' => single(Token::Equals, self),
            b';' => single(Token::Semicolon, self),
            b'$' => single(Token::Dollar, self),
            b'*' => single(Token::Star, self),
            b'#' => {
                self.pos += 1;
                let digits = self.take_while(|c| c.is_ascii_digit());
                digits
                    .parse::<u64>()
                    .map(Token::Ref)
                    .map_err(|_| self.err(format!("'#{digits}' is not an instance name")))
            }
            b'\'' => self.string(),
            b'"' => {
                self.pos += 1;
                let hex = self.take_while(|c| c.is_ascii_hexdigit()).to_string();
                if self.bytes.get(self.pos) != Some(&b'"') {
                    return Err(self.err("a binary value that is not closed by '\"'"));
                }
                self.pos += 1;
                Ok(Token::Binary(hex))
            }
            b'.' if self
                .bytes
                .get(self.pos + 1)
                .is_some_and(|c| c.is_ascii_alphabetic() || *c == b'_') =>
            {
                self.pos += 1;
                let name = self
                    .take_while(|c| c.is_ascii_alphanumeric() || c == b'_')
                    .to_ascii_uppercase();
                if self.bytes.get(self.pos) != Some(&b'.') {
                    return Err(self.err(format!("enumeration '.{name}' is not closed by '.'")));
                }
                self.pos += 1;
                Ok(Token::Enum(name))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => self.number(),
            b'!' | b'A'..=b'Z' | b'a'..=b'z' | b'_' => {
                let word = self
                    .take_while(|c| {
                        c.is_ascii_alphanumeric() || c == b'_' || c == b'-' || c == b'!'
                    })
                    .to_ascii_uppercase();
                Ok(Token::Keyword(word))
            }
            other => Err(self.err(format!(
                "unexpected character '{}'",
                (other as char).escape_default()
            ))),
        }
    }

    fn take_while(&mut self, keep: impl Fn(u8) -> bool) -> &'a str {
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|&c| keep(c)) {
            self.pos += 1;
        }
        // Only ASCII bytes are kept, so this is valid UTF-8.
        std::str::from_utf8(&self.bytes[start..self.pos]).unwrap_or("")
    }

    fn number(&mut self) -> Result<Token, SyntaxError> {
        let text = self
            .take_while(|c| c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.' | b'E' | b'e'));
        if !text.contains(['.', 'E', 'e']) {
            return text
                .parse::<i64>()
                .map(Token::Int)
                .map_err(|_| self.err(format!("'{text}' is not an integer")));
        }
        // Part 21 writes "1." and "1.E-5"; Rust's parser wants a digit after the dot.
        let fixed = text.replace(".E", ".0E").replace(".e", ".0e");
        let fixed = if fixed.ends_with('.') {
            format!("{fixed}0")
        } else {
            fixed
        };
        match fixed.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Token::Real(x)),
            Ok(_) => Err(self.err(format!("'{text}' is not a finite number"))),
            Err(_) => Err(self.err(format!("'{text}' is not a number"))),
        }
    }

    /// A string between apostrophes: `''` is an apostrophe, `\\` a
    /// backslash, `\X2\…\X0\` UTF-16 and `\X4\…\X0\` UTF-32 hex, `\X\hh`
    /// an ISO 8859-1 byte, `\S\c` a character of its upper half.
    fn string(&mut self) -> Result<Token, SyntaxError> {
        let start = self.line;
        self.pos += 1;
        let mut raw = Vec::new();
        loop {
            match self.bytes.get(self.pos) {
                None => {
                    return Err(SyntaxError {
                        line: start,
                        entity: None,
                        message: "a string that is never closed (')".into(),
                    });
                }
                Some(b'\'') if self.bytes.get(self.pos + 1) == Some(&b'\'') => {
                    raw.push(b'\'');
                    self.pos += 2;
                }
                Some(b'\'') => {
                    self.pos += 1;
                    break;
                }
                Some(&c) => {
                    if c == b'\n' {
                        self.line += 1;
                    }
                    raw.push(c);
                    self.pos += 1;
                }
            }
        }
        Ok(Token::Str(decode_string(&String::from_utf8_lossy(&raw))))
    }
}

/// Decodes Part 21 string escapes (unknown ones are kept as they are).
fn decode_string(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(i) = rest.find('\\') {
        out.push_str(&rest[..i]);
        rest = &rest[i..];
        let hex_run = |r: &str, width: usize| -> Option<(String, usize)> {
            let end = r.find("\\X0\\")?;
            let body = &r[..end];
            if !body.len().is_multiple_of(width) || !body.bytes().all(|c| c.is_ascii_hexdigit()) {
                return None;
            }
            let mut text = String::new();
            let units: Vec<u32> = (0..body.len() / width)
                .map(|k| u32::from_str_radix(&body[k * width..(k + 1) * width], 16).unwrap_or(0))
                .collect();
            if width == 4 {
                let u16s: Vec<u16> = units.iter().map(|&u| u as u16).collect();
                text.push_str(&String::from_utf16_lossy(&u16s));
            } else {
                text.extend(
                    units
                        .iter()
                        .map(|&u| char::from_u32(u).unwrap_or('\u{fffd}')),
                );
            }
            Some((text, end + 4))
        };
        if let Some(r) = rest.strip_prefix("\\\\") {
            out.push('\\');
            rest = r;
        } else if let Some(r) = rest.strip_prefix("\\X2\\")
            && let Some((text, used)) = hex_run(r, 4)
        {
            out.push_str(&text);
            rest = &r[used..];
        } else if let Some(r) = rest.strip_prefix("\\X4\\")
            && let Some((text, used)) = hex_run(r, 8)
        {
            out.push_str(&text);
            rest = &r[used..];
        } else if let Some(r) = rest.strip_prefix("\\X\\")
            && r.len() >= 2
            && let Ok(b) = u8::from_str_radix(r.get(..2).unwrap_or("zz"), 16)
        {
            out.push(b as char);
            rest = &r[2..];
        } else if let Some(r) = rest.strip_prefix("\\S\\")
            && let Some(c) = r.chars().next()
            && c.is_ascii()
        {
            out.push(char::from(c as u8 + 128));
            rest = &r[1..];
        } else {
            out.push('\\');
            rest = &rest[1..];
        }
    }
    out.push_str(rest);
    out
}

/// Encodes `s` as a Part 21 string body: `'` doubled, `\` doubled, and
/// characters outside printable ASCII as `\X2\…\X0\` (UTF-16 hex).
pub fn encode_string(s: &str) -> String {
    let mut out = String::new();
    let mut wide = String::new();
    let flush = |out: &mut String, wide: &mut String| {
        if !wide.is_empty() {
            out.push_str("\\X2\\");
            out.push_str(wide);
            out.push_str("\\X0\\");
            wide.clear();
        }
    };
    for c in s.chars() {
        if (' '..='~').contains(&c) {
            flush(&mut out, &mut wide);
            match c {
                '\'' => out.push_str("''"),
                '\\' => out.push_str("\\\\"),
                _ => out.push(c),
            }
        } else {
            let mut units = [0u16; 2];
            for u in c.encode_utf16(&mut units) {
                wide.push_str(&format!("{u:04X}"));
            }
        }
    }
    flush(&mut out, &mut wide);
    out
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<(Token, u32)>,
    entity: Option<u64>,
}

impl Parser<'_> {
    fn peek(&mut self) -> Result<&Token, SyntaxError> {
        if self.peeked.is_none() {
            let t = self.lexer.next().map_err(|e| self.with_entity(e))?;
            self.peeked = Some((t, self.lexer.line));
        }
        Ok(&self.peeked.as_ref().expect("just filled").0)
    }
    fn take(&mut self) -> Result<Token, SyntaxError> {
        self.peek()?;
        Ok(self.peeked.take().expect("peeked").0)
    }
    fn with_entity(&self, mut e: SyntaxError) -> SyntaxError {
        e.entity = e.entity.or(self.entity);
        e
    }
    fn err(&self, message: impl Into<String>) -> SyntaxError {
        SyntaxError {
            line: self.lexer.line,
            entity: self.entity,
            message: message.into(),
        }
    }
    fn expect(&mut self, want: Token, what: &str) -> Result<(), SyntaxError> {
        let got = self.take()?;
        if got == want {
            Ok(())
        } else {
            Err(self.err(format!("expected {what}, found {}", describe(&got))))
        }
    }
    fn keyword(&mut self, what: &str) -> Result<String, SyntaxError> {
        match self.take()? {
            Token::Keyword(k) => Ok(k),
            other => Err(self.err(format!("expected {what}, found {}", describe(&other)))),
        }
    }

    /// `( p, p, … )` after its opening parenthesis has been seen.
    fn list(&mut self, depth: usize) -> Result<Vec<Param>, SyntaxError> {
        if depth > MAX_DEPTH {
            return Err(self.err(format!("lists nest more than {MAX_DEPTH} deep")));
        }
        self.expect(Token::Open, "'('")?;
        let mut out = Vec::new();
        if *self.peek()? == Token::Close {
            self.take()?;
            return Ok(out);
        }
        loop {
            if out.len() >= MAX_LIST {
                return Err(self.err(format!("a list of more than {MAX_LIST} values")));
            }
            out.push(self.param(depth)?);
            match self.take()? {
                Token::Comma => {}
                Token::Close => return Ok(out),
                other => {
                    return Err(self.err(format!(
                        "expected ',' or ')' in a list, found {}",
                        describe(&other)
                    )));
                }
            }
        }
    }

    fn param(&mut self, depth: usize) -> Result<Param, SyntaxError> {
        // Typed values nest too (`A(A(A(…)))`): the same limit.
        if depth > MAX_DEPTH {
            return Err(self.err(format!("values nest more than {MAX_DEPTH} deep")));
        }
        if *self.peek()? == Token::Open {
            return Ok(Param::List(self.list(depth + 1)?));
        }
        Ok(match self.take()? {
            Token::Int(i) => Param::Int(i),
            Token::Real(x) => Param::Real(x),
            Token::Str(s) => Param::Str(s),
            Token::Enum(e) => Param::Enum(e),
            Token::Ref(r) => Param::Ref(r),
            Token::Binary(b) => Param::Binary(b),
            Token::Dollar => Param::Unset,
            Token::Star => Param::Derived,
            Token::Keyword(k) => {
                self.expect(Token::Open, "'(' after a type name")?;
                let inner = self.param(depth + 1)?;
                self.expect(Token::Close, "')' closing a typed value")?;
                Param::Typed(k, Box::new(inner))
            }
            other => return Err(self.err(format!("expected a value, found {}", describe(&other)))),
        })
    }

    /// `NAME(params)`.
    fn record(&mut self, depth: usize) -> Result<Record, SyntaxError> {
        let name = self.keyword("an entity name")?;
        let params = self.list(depth)?;
        Ok(Record { name, params })
    }
}

fn describe(t: &Token) -> String {
    match t {
        Token::Keyword(k) => format!("'{k}'"),
        Token::Int(i) => format!("the number {i}"),
        Token::Real(x) => format!("the number {x}"),
        Token::Str(_) => "a string".into(),
        Token::Enum(e) => format!("'.{e}.'"),
        Token::Ref(r) => format!("'#{r}'"),
        Token::Binary(_) => "a binary value".into(),
        Token::Open => "'('".into(),
        Token::Close => "')'".into(),
        Token::Comma => "','".into(),
        Token::Equals => "'='".into(),
        Token::Semicolon => "';'".into(),
        Token::Dollar => "'$'".into(),
        Token::Star => "'*'".into(),
        Token::End => "the end of the file".into(),
    }
}

/// Parses an exchange structure.
///
/// # Errors
/// A [`SyntaxError`] naming the line (and the instance, inside one): a
/// missing section, a malformed record, a repeated id, a limit passed.
pub fn parse(text: &[u8]) -> Result<Exchange, SyntaxError> {
    let mut p = Parser {
        lexer: Lexer {
            bytes: text,
            pos: 0,
            line: 1,
        },
        peeked: None,
        entity: None,
    };
    let magic = p.keyword("'ISO-10303-21;' at the start of a STEP file")?;
    if magic != "ISO-10303-21" {
        return Err(p.err(format!(
            "not a STEP file: it starts with '{magic}', not 'ISO-10303-21;'"
        )));
    }
    p.expect(Token::Semicolon, "';'")?;
    let mut ex = Exchange::default();
    if p.keyword("HEADER")? != "HEADER" {
        return Err(p.err("expected the HEADER section"));
    }
    p.expect(Token::Semicolon, "';'")?;
    loop {
        if matches!(p.peek()?, Token::Keyword(k) if k == "ENDSEC") {
            p.take()?;
            p.expect(Token::Semicolon, "';'")?;
            break;
        }
        let r = p.record(0)?;
        p.expect(Token::Semicolon, "';' after a header record")?;
        ex.header.push(r);
    }
    loop {
        let word = p.keyword("DATA or END-ISO-10303-21")?;
        match word.as_str() {
            "END-ISO-10303-21" => break,
            "DATA" => {}
            other => return Err(p.err(format!("expected DATA, found '{other}'"))),
        }
        if *p.peek()? == Token::Open {
            p.list(0)?;
        }
        p.expect(Token::Semicolon, "';' after DATA")?;
        loop {
            match p.take()? {
                Token::Keyword(k) if k == "ENDSEC" => {
                    p.expect(Token::Semicolon, "';'")?;
                    break;
                }
                Token::Ref(id) => {
                    let line = p.lexer.line;
                    p.entity = Some(id);
                    if ex.instances.contains_key(&id) {
                        return Err(p.err(format!("#{id} is defined twice")));
                    }
                    if ex.instances.len() >= MAX_ENTITIES {
                        return Err(p.err(format!("more than {MAX_ENTITIES} instances")));
                    }
                    p.expect(Token::Equals, "'=' after the instance name")?;
                    let (records, complex) = if *p.peek()? == Token::Open {
                        p.take()?;
                        let mut records = Vec::new();
                        while *p.peek()? != Token::Close {
                            if records.len() >= MAX_DEPTH * 4 {
                                return Err(p.err("a complex instance of too many parts"));
                            }
                            records.push(p.record(1)?);
                        }
                        p.take()?;
                        if records.is_empty() {
                            return Err(p.err("a complex instance without parts"));
                        }
                        (records, true)
                    } else {
                        (vec![p.record(0)?], false)
                    };
                    p.expect(Token::Semicolon, "';' after the instance")?;
                    p.entity = None;
                    ex.instances.insert(
                        id,
                        Instance {
                            line,
                            records,
                            complex,
                        },
                    );
                    ex.order.push(id);
                }
                Token::End => {
                    return Err(p.err("the file ends inside the DATA section (no ENDSEC)"));
                }
                other => {
                    return Err(p.err(format!(
                        "expected an instance '#n = …' or ENDSEC, found {}",
                        describe(&other)
                    )));
                }
            }
        }
    }
    Ok(ex)
}

impl Exchange {
    /// Refuses a cycle of references (`#1` refers to `#2` which refers to
    /// `#1`): the geometry and topology read here never refer back.
    ///
    /// # Errors
    /// The instance where the cycle closes, its line and the cycle.
    pub fn check_acyclic(&self) -> Result<(), SyntaxError> {
        // 0: unseen, 1: on the stack, 2: done.
        let mut state: HashMap<u64, u8> = HashMap::with_capacity(self.instances.len());
        for &root in &self.order {
            if state.get(&root).copied().unwrap_or(0) != 0 {
                continue;
            }
            // Iterative DFS: (id, its references, next index).
            let mut stack: Vec<(u64, Vec<u64>, usize)> = vec![(root, self.references(root), 0)];
            state.insert(root, 1);
            while let Some((id, refs, next)) = stack.last_mut() {
                if *next >= refs.len() {
                    state.insert(*id, 2);
                    stack.pop();
                    continue;
                }
                let r = refs[*next];
                *next += 1;
                match state.get(&r).copied().unwrap_or(0) {
                    1 => {
                        let from = stack.iter().position(|s| s.0 == r).unwrap_or(0);
                        let cycle: Vec<String> = stack[from..]
                            .iter()
                            .map(|s| format!("#{}", s.0))
                            .chain([format!("#{r}")])
                            .collect();
                        return Err(SyntaxError {
                            line: self.instances.get(&r).map_or(0, |i| i.line),
                            entity: Some(r),
                            message: format!("a cycle of references: {}", cycle.join(" → ")),
                        });
                    }
                    0 if self.instances.contains_key(&r) => {
                        state.insert(r, 1);
                        let refs = self.references(r);
                        stack.push((r, refs, 0));
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// The ids an instance refers to, in order.
    fn references(&self, id: u64) -> Vec<u64> {
        fn walk(p: &Param, out: &mut Vec<u64>) {
            match p {
                Param::Ref(r) => out.push(*r),
                Param::List(l) => l.iter().for_each(|x| walk(x, out)),
                Param::Typed(_, x) => walk(x, out),
                _ => {}
            }
        }
        let mut out = Vec::new();
        if let Some(i) = self.instances.get(&id) {
            for r in &i.records {
                r.params.iter().for_each(|p| walk(p, &mut out));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_and_complex_instances_with_lines_strings_and_numbers() {
        let text = b"ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('it''s \\X2\\00E9\\X0\\',(1.,-2.5E-3,3));\n/* a comment */\n#2 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n#3 = X(LENGTH_MEASURE(1.E-07),$,#1);\nENDSEC;\nEND-ISO-10303-21;\n";
        let ex = parse(text).unwrap();
        assert_eq!(ex.order, vec![1, 2, 3]);
        let p = &ex.instances[&1];
        assert_eq!(p.line, 6);
        assert_eq!(p.records[0].params[0], Param::Str("it's é".into()));
        assert_eq!(
            p.records[0].params[1],
            Param::List(vec![Param::Real(1.0), Param::Real(-2.5e-3), Param::Int(3)])
        );
        let u = &ex.instances[&2];
        assert!(u.complex);
        assert_eq!(u.line, 8);
        assert_eq!(u.records.len(), 3);
        assert_eq!(u.records[2].params[0], Param::Enum("MILLI".into()));
        assert_eq!(
            ex.instances[&3].records[0].params[0],
            Param::Typed("LENGTH_MEASURE".into(), Box::new(Param::Real(1e-7)))
        );
        ex.check_acyclic().unwrap();
    }

    #[test]
    fn strings_round_trip_through_the_escapes() {
        for s in ["plain", "it's", "back\\slash", "Würfel ☃ 𝄞"] {
            let text = format!(
                "ISO-10303-21;HEADER;ENDSEC;DATA;#1=A('{}');ENDSEC;END-ISO-10303-21;",
                encode_string(s)
            );
            let ex = parse(text.as_bytes()).unwrap();
            assert_eq!(ex.instances[&1].records[0].params[0], Param::Str(s.into()));
        }
    }

    #[test]
    fn errors_name_the_line_and_the_instance() {
        let e = parse(b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=A(1,2);\n#2=B(1,,2);\nENDSEC;END-ISO-10303-21;").unwrap_err();
        assert_eq!((e.line, e.entity), (6, Some(2)), "{e}");
        let e =
            parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A(1);\n#1=A(2);ENDSEC;END-ISO-10303-21;")
                .unwrap_err();
        assert!(e.to_string().contains("#1 is defined twice"), "{e}");
        let e = parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A(1);\n#2=A((((((((((((((((((((1))))))))))))))))))));").unwrap_err();
        assert!(e.to_string().contains("nest more than"), "{e}");
        let deep = format!(
            "ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A({}1{});",
            "B(".repeat(100_000),
            ")".repeat(100_000)
        );
        let e = parse(deep.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("nest more than"), "{e}");
        let e = parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A(1);\n#2=A('abc").unwrap_err();
        assert!(e.to_string().contains("never closed"), "{e}");
        let e = parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A(1);").unwrap_err();
        assert!(e.to_string().contains("no ENDSEC"), "{e}");
        let e = parse(b"solid x\n").unwrap_err();
        assert!(e.to_string().contains("not a STEP file"), "{e}");
        let e = parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;#1=A(1E999);ENDSEC;END-ISO-10303-21;")
            .unwrap_err();
        assert!(e.to_string().contains("finite"), "{e}");
    }

    #[test]
    fn cycles_are_found_and_named() {
        let ex = parse(b"ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=A(#2);\n#2=B((#3));\n#3=C(#1);\n#4=D(#4);ENDSEC;END-ISO-10303-21;").unwrap();
        let e = ex.check_acyclic().unwrap_err();
        assert!(e.message.contains("#1 → #2 → #3 → #1"), "{e}");
        assert_eq!(e.entity, Some(1));
    }
}
