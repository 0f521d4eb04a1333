//! Rust source read as tokens with their line numbers, for the checks of the code's shape:
//! comments, character literals and the items under `#[cfg(test)]` are left out; a string
//! literal is one token.

/// One token (an identifier, `::`, a single punctuation character or a string literal with its
/// quotes) and its 1-based line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Token {
    pub text: String,
    pub line: usize,
}

impl Token {
    pub(crate) fn is(&self, text: &str) -> bool {
        self.text == text
    }

    pub(crate) fn is_ident(&self) -> bool {
        self.text.chars().all(|c| c.is_alphanumeric() || c == '_')
    }

    /// The content of a string literal token (`"mu_s"` → `mu_s`), `None` for other tokens.
    pub(crate) fn string(&self) -> Option<&str> {
        self.text.strip_prefix('"')?.strip_suffix('"')
    }
}

/// The tokens of the non-test code of `text`.
pub(crate) fn code_tokens(text: &str) -> Vec<Token> {
    without_test_items(tokenize(text))
}

/// The index after the (nested) block comment starting at `i`.
fn block_comment_end(chars: &[char], mut i: usize) -> usize {
    let mut depth = 0;
    while i < chars.len() {
        if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
            depth += 1;
            i += 2;
        } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    i
}

/// The index after the string literal starting at `i` (escapes skipped).
fn string_end(chars: &[char], mut i: usize) -> usize {
    i += 1;
    while i < chars.len() && chars[i] != '"' {
        i += if chars[i] == '\\' { 2 } else { 1 };
    }
    i + 1
}

/// Whether a raw string (`r"…"`, `r#"…"#`) starts at `i` (not an identifier ending in `r`).
fn raw_string_at(chars: &[char], i: usize) -> bool {
    let ident_char = |k: usize| chars[k].is_alphanumeric() || chars[k] == '_';
    // `br"…"` is a raw byte string; any other letter before `r` makes it an identifier.
    let byte_prefix = i > 0 && chars[i - 1] == 'b' && (i < 2 || !ident_char(i - 2));
    let after_ident = i > 0 && ident_char(i - 1) && !byte_prefix;
    let mut j = i + 1;
    while chars.get(j) == Some(&'#') {
        j += 1;
    }
    !after_ident && chars.get(j) == Some(&'"')
}

/// The index after the raw string starting at `i`.
fn raw_string_end(chars: &[char], i: usize) -> usize {
    let mut j = i + 1;
    let mut hashes = 0;
    while chars[j] == '#' {
        hashes += 1;
        j += 1;
    }
    j += 1;
    while j < chars.len() {
        if chars[j] == '"' && (1..=hashes).all(|h| chars.get(j + h) == Some(&'#')) {
            return j + 1 + hashes;
        }
        j += 1;
    }
    j
}

/// The length of a character literal at `i` (`'a'`, `'\n'`, `'\u{1F600}'`); `None` for a
/// lifetime or a label (`'a`).
fn char_literal_len(chars: &[char], i: usize) -> Option<usize> {
    if chars.get(i + 1) == Some(&'\\') {
        let end = (i + 2..chars.len().min(i + 12)).find(|&j| chars[j] == '\'')?;
        return Some(end - i + 1);
    }
    (chars.get(i + 2) == Some(&'\'')).then_some(3)
}

/// Identifiers, `::`, single punctuation characters and string literals (a token `"…"` holding
/// the literal's content, raw and byte strings included), with their lines; comments and
/// character literals are left out.
fn tokenize(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        let mut token = None;
        let end = if c == '/' && next == Some('/') {
            (i..chars.len())
                .find(|&j| chars[j] == '\n')
                .unwrap_or(chars.len())
        } else if c == '/' && next == Some('*') {
            block_comment_end(&chars, i)
        } else if let Some(len) = (c == '\'').then(|| char_literal_len(&chars, i)).flatten() {
            i + len
        } else if c == '"' || (c == 'r' && raw_string_at(&chars, i)) {
            let (end, content) = string_literal(&chars, i);
            token = Some(format!("\"{content}\""));
            end
        } else if c.is_alphanumeric() || c == '_' {
            let end = (i..chars.len())
                .find(|&j| !(chars[j].is_alphanumeric() || chars[j] == '_'))
                .unwrap_or(chars.len());
            // `b"…"` and `br"…"` are byte strings: their `b` is no identifier.
            let word = &chars[i..end];
            let byte_string = (word == ['b'] && chars.get(end) == Some(&'"'))
                || (word == ['b', 'r'] && raw_string_at(&chars, i + 1));
            if byte_string {
                i + 1
            } else {
                token = Some(word.iter().collect());
                end
            }
        } else if c == ':' && next == Some(':') {
            token = Some(String::from("::"));
            i + 2
        } else {
            token = (!c.is_whitespace()).then(|| c.to_string());
            i + 1
        };
        if let Some(text) = token {
            tokens.push(Token { text, line });
        }
        let end = end.min(chars.len());
        line += chars[i..end].iter().filter(|&&c| c == '\n').count();
        i = end;
    }
    tokens
}

/// The end of the string literal (plain or raw) at `i` and its content.
fn string_literal(chars: &[char], i: usize) -> (usize, String) {
    if chars[i] == '"' {
        let end = string_end(chars, i).min(chars.len());
        (
            end,
            chars[i + 1..end.saturating_sub(1).max(i + 1)]
                .iter()
                .collect(),
        )
    } else {
        let end = raw_string_end(chars, i).min(chars.len());
        let hashes = chars[i + 1..].iter().take_while(|&&c| c == '#').count();
        let content = &chars[(i + 2 + hashes).min(end)..end.saturating_sub(1 + hashes)];
        (end, content.iter().collect())
    }
}

/// The tokens without the items under `#[cfg(test)]` (a test module or a test-only item).
fn without_test_items(tokens: Vec<Token>) -> Vec<Token> {
    const CFG_TEST: [&str; 7] = ["#", "[", "cfg", "(", "test", ")", "]"];
    let mut out = Vec::with_capacity(tokens.len());
    let mut i = 0;
    while i < tokens.len() {
        let is_cfg_test = tokens
            .get(i..i + CFG_TEST.len())
            .is_some_and(|t| t.iter().zip(CFG_TEST).all(|(a, b)| a.is(b)));
        if !is_cfg_test {
            out.push(tokens[i].clone());
            i += 1;
            continue;
        }
        i = item_end(&tokens, i + CFG_TEST.len());
    }
    out
}

/// The index after the item starting at `i`: after its `;` or its balanced `{ … }`.
pub(crate) fn item_end(tokens: &[Token], mut i: usize) -> usize {
    let mut depth = 0usize;
    while i < tokens.len() {
        match tokens[i].text.as_str() {
            "{" => depth += 1,
            "}" => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    return i + 1;
                }
            }
            ";" if depth == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    i
}

/// The functions with a body: (name, first line, last line).
pub(crate) fn functions(tokens: &[Token]) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        let Some(name) = tokens.get(i + 1).filter(|n| t.is("fn") && n.is_ident()) else {
            continue;
        };
        // The body is the first `{` before any `;` (a declaration without body has none).
        let Some(open) = tokens[i..]
            .iter()
            .position(|t| t.is("{") || t.is(";"))
            .map(|p| i + p)
            .filter(|&p| tokens[p].is("{"))
        else {
            continue;
        };
        let close = item_end(tokens, open) - 1;
        out.push((name.text.clone(), t.line, tokens[close].line));
    }
    out
}

#[test]
fn tokens_keep_their_lines_without_comments_strings_and_tests() {
    let text = "fn a() {\n    let s = \"{ not a brace\n }\"; // }\n    /* {\n */ 'x';\n}\n\
                #[cfg(test)]\nmod tests {\n fn t() {}\n}\nfn b<'a>(x: &'a str) -> fn(u8) { g }\n";
    let tokens = code_tokens(text);
    assert_eq!(
        functions(&tokens),
        vec![(String::from("a"), 1, 6), (String::from("b"), 11, 11)]
    );
    assert!(tokens.iter().all(|t| !t.is("tests") && !t.is("not")));
    assert!(tokens
        .iter()
        .any(|t| t.string() == Some("{ not a brace\n }")));
    let raw = code_tokens("let a = r#\"x\"y\"#; let b = br\"z\"; let c = b\"w\";");
    let strings: Vec<&str> = raw.iter().filter_map(Token::string).collect();
    assert_eq!(strings, ["x\"y", "z", "w"]);
}
