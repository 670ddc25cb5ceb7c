//! Every committed proptest regression file is replayed: proptest reads
//! `PACKAGE/proptest-regressions/PATH.txt` for the property tests in
//! `PACKAGE/src/PATH.rs` (the root package and each of `crates/*`)
//! (its default `FileFailurePersistence::SourceParallel`, found from the
//! source file of the `proptest!` block) and runs those cases before any
//! new one. A file whose source moved or lost its property tests would be
//! read by no test and its cases would silently stop running (issue 31, P1:
//! a star case that failed at random in CI).

use std::path::{Path, PathBuf};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// The workspace's packages: the root and each directory of `crates/`.
fn packages(root: &Path) -> Vec<PathBuf> {
    let mut out = vec![root.to_path_buf()];
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").is_file())
        .collect();
    crates.sort();
    out.extend(crates);
    out
}

#[test]
fn every_regression_file_belongs_to_a_source_file_with_property_tests() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = vec![];
    for package in packages(root) {
        let dir = package.join("proptest-regressions");
        if dir.is_dir() {
            let mut here = vec![];
            files(&dir, &mut here);
            found.extend(here.into_iter().map(|f| (package.clone(), dir.clone(), f)));
        }
    }
    assert!(
        !found.is_empty(),
        "no regression files under any package's proptest-regressions/"
    );
    for (package, dir, f) in found {
        let rel = f.strip_prefix(&dir).unwrap().with_extension("rs");
        let src = package.join("src").join(&rel);
        let text = std::fs::read_to_string(&src).unwrap_or_else(|_| {
            panic!(
                "{} has no source file {} to replay it: move it with its source",
                f.display(),
                src.display()
            )
        });
        assert!(
            text.contains("proptest!"),
            "{} holds no proptest! block to replay {}",
            src.display(),
            f.display()
        );
        // Each line a seed proptest can read (`cc <64 hex>`, `pt <hex>`) or a comment.
        for (i, line) in std::fs::read_to_string(&f).unwrap().lines().enumerate() {
            let t = line.trim();
            if t.is_empty() || t.starts_with('#') {
                continue;
            }
            let mut parts = t.split_whitespace();
            let (alg, seed) = (parts.next().unwrap(), parts.next().unwrap_or(""));
            assert!(
                matches!(alg, "cc" | "pt" | "xs")
                    && !seed.is_empty()
                    && seed.chars().all(|c| c.is_ascii_hexdigit()),
                "{}:{}: not a proptest seed line: {line}",
                f.display(),
                i + 1
            );
        }
    }
}
