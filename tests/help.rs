//! Every help page teaches with an example (house rule): `basr --help` and
//! `basr <command> --help` / `-h` for each command the top-level help lists,
//! so a command added later without an example fails here.

use assert_cmd::Command;

fn help(args: &[&str]) -> String {
    let out = Command::cargo_bin("basr")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "basr {args:?}");
    String::from_utf8(out.stdout).unwrap()
}

/// The command names under "Commands:" in the top-level help.
fn commands() -> Vec<String> {
    let top = help(&["--help"]);
    let names: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        // A long description wraps onto deeper-indented lines.
        .filter(|l| !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next().map(String::from))
        .filter(|n| n != "help")
        .collect();
    assert!(names.len() >= 9, "commands found: {names:?}");
    names
}

#[test]
fn top_level_help_has_examples_and_exit_codes() {
    let top = help(&["--help"]);
    assert!(top.contains("Examples:"), "{top}");
    assert!(top.contains("basr compile STOP"), "{top}");
    for code in [
        "0 success",
        "1 verdict negative",
        "2 bad input",
        "130 interrupted",
    ] {
        assert!(top.contains(code), "exit code {code:?} in:\n{top}");
    }
}

#[test]
fn the_command_list_is_one_line_each() {
    let top = help(&["--help"]);
    let listed = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .count();
    assert_eq!(listed, commands().len() + 1, "with help:\n{top}");
}

#[test]
fn every_command_help_shows_an_example_of_itself() {
    for name in commands() {
        for flag in ["--help", "-h"] {
            let page = help(&[&name, flag]);
            assert!(
                page.contains("Example"),
                "basr {name} {flag} has no example:\n{page}"
            );
            let usage = format!("basr {name} ");
            let example_lines = page
                .lines()
                .skip_while(|l| !l.starts_with("Example"))
                .filter(|l| l.trim_start().starts_with(&usage))
                .count();
            assert!(
                example_lines >= 1,
                "basr {name} {flag}: no example line starting {usage:?}:\n{page}"
            );
        }
    }
}
