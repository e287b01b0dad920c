//! The parser corpus: every valid file parses (with spot checks of what it holds), and every
//! malformed file fails at the line and column its `.expect` sidecar names, with the expected
//! words in the message. `parser_corpus/generate_malformed.py` wrote the malformed files.

use std::path::{Path, PathBuf};

use fsim::case::{read_dict_file, Dict, Value};

fn corpus(kind: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/parser_corpus")
        .join(kind)
}

fn valid(name: &str) -> Dict {
    let dir = corpus("valid");
    read_dict_file(&dir.join(name), Some(&dir)).unwrap_or_else(|e| panic!("{}", e.report()))
}

#[test]
fn every_valid_file_parses() {
    let dir = corpus("valid");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if let Err(e) = read_dict_file(&path, Some(&dir)) {
            panic!("{}", e.report());
        }
        count += 1;
    }
    assert!(count >= 15, "only {count} valid files");
}

#[test]
fn valid_files_hold_what_they_say() {
    let c = valid("controlDict");
    assert_eq!(c.get_word("startFrom").unwrap(), "latestTime");
    assert_eq!(c.get_scalar("deltaT").unwrap(), 1e-4);
    assert!(c.get_bool("adjustTimeStep").unwrap());
    assert!(!c.get_bool("writeCompression").unwrap());
    assert_eq!(c.get_label("timePrecision").unwrap(), 6);
    let probes = c.get_dict("functions").unwrap().get_dict("probes").unwrap();
    let locations = &probes.get_tokens("probeLocations").unwrap()[0];
    let second = locations.as_list().unwrap().get(1).unwrap().as_vector();
    assert_eq!(second, Some([1e-2, -2.5e-3, 0.0]));
    assert_eq!(
        c.get_dict("functions").unwrap().directives[0].argument,
        "residuals"
    );

    let b = valid("blockMeshDict");
    let vertices = &b.get_tokens("vertices").unwrap()[0];
    // `$L` expanded inside the list.
    assert_eq!(
        vertices.as_list().unwrap().get(6).unwrap().as_vector(),
        Some([10.0, 10.0, -1.0])
    );
    let blocks = b.get_tokens("blocks").unwrap()[0].as_list().unwrap();
    assert_eq!(blocks.get(0).unwrap().as_word(), Some("hex"));
    assert_eq!(blocks.get(2).unwrap().as_vector(), Some([20.0, 20.0, 1.0]));

    let t = valid("transportProperties.icoFoam");
    assert_eq!(t.get_scalar("nu").unwrap(), 0.01);
    assert_eq!(t.get_scalar("DT").unwrap(), 4e-5);
    assert_eq!(t.get_vector("Ubar").unwrap(), [0.1, 0.0, 0.0]);

    let u = valid("U.air");
    let bf = u.get_dict("boundaryField").unwrap();
    assert_eq!(
        bf.get_dict("top").unwrap().get_word("type").unwrap(),
        "noSlip"
    );
    assert_eq!(
        bf.get_dict("leftWall2").unwrap().get_word("type").unwrap(),
        "fixedValue"
    );
    assert_eq!(
        bf.get_dict("nanoParticle")
            .unwrap()
            .get_word("type")
            .unwrap(),
        "slip"
    );
    let fixed = bf.get_dict("aWall").unwrap().get_tokens("value").unwrap();
    assert_eq!(fixed[1].as_vector(), Some([1e-3, -2e-3, 350.0]));

    let positions = valid("kinematicCloudPositions");
    assert_eq!(positions.values[0].as_list().unwrap().len(), 3);
    let points = valid("points.gz");
    assert_eq!(
        points.values[0]
            .as_list()
            .unwrap()
            .get(2)
            .unwrap()
            .as_vector(),
        Some([1.0, 1.0, 0.0])
    );

    let s = valid("fvSchemes");
    let div = s.get_dict("divSchemes").unwrap();
    assert_eq!(div.get_tokens("div(phi,U)").unwrap().len(), 3);
    assert!(div.contains("div(((alpha.air*nuEff.air)*dev2(T(grad(U.air)))))"));

    let f = valid("fvSolution");
    let p_final = f.get_dict("solvers").unwrap().get_dict("pFinal").unwrap();
    assert_eq!(p_final.get_word("solver").unwrap(), "GAMG");
    assert_eq!(p_final.get_scalar("relTol").unwrap(), 0.0);
    let u_solver = f
        .get_dict("solvers")
        .unwrap()
        .get_dict("U.airFinal")
        .unwrap();
    assert_eq!(u_solver.get_word("solver").unwrap(), "smoothSolver");
    assert_eq!(
        f.get_dict("fsim").unwrap().get_word("timeScheme").unwrap(),
        "rk2"
    );

    let a = valid("alpha.air");
    let field = a.get_tokens("internalField").unwrap();
    assert_eq!(
        field[2].as_list().unwrap().get(3).unwrap().as_scalar(),
        Some(0.8)
    );
    let zone = &a.get_tokens("cellZoneValues").unwrap()[1];
    assert!(matches!(zone.value, Value::UniformList(3, _)));
    assert_eq!(
        a.get_tokens("emptyList").unwrap()[1]
            .as_list()
            .unwrap()
            .len(),
        0
    );

    let sf = valid("setFieldsDict");
    assert!(!sf.contains("unwanted"));
    let geometry = sf.get_dict("geometry").unwrap();
    assert_eq!(geometry.get_scalar("radius").unwrap(), 0.25);
    assert_eq!(geometry.get_vector("centre").unwrap(), [0.0, 0.25, 0.0]);
    assert_eq!(
        geometry
            .get_dict("inner")
            .unwrap()
            .get_scalar("scaled")
            .unwrap(),
        0.25
    );

    let t = valid("T.codeStream");
    let field = t.get_tokens("internalField").unwrap();
    assert!(matches!(&field[0].value, Value::Directive(d) if d == "codeStream"));
    let code = field[1].as_dict().unwrap().get_tokens("code").unwrap();
    assert!(matches!(&code[0].value, Value::Code(c) if c.contains("unbalanced")));
}

#[test]
fn every_malformed_file_fails_where_its_sidecar_says() {
    let dir = corpus("malformed");
    let mut checked = 0;
    let mut mismatches = Vec::new();
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "expect"))
        .collect();
    names.sort();
    for expect_path in names {
        let input = expect_path.with_extension("");
        let expect = std::fs::read_to_string(&expect_path).unwrap();
        let mut lines = expect.lines();
        let mut numbers = lines.next().unwrap().split_whitespace();
        let line: usize = numbers.next().unwrap().parse().unwrap();
        let col: usize = numbers.next().unwrap().parse().unwrap();
        let words = lines.next().unwrap();
        let file = lines
            .next()
            .and_then(|l| l.strip_prefix("file "))
            .map(str::to_string)
            .unwrap_or_else(|| input.file_name().unwrap().to_string_lossy().into_owned());
        let err = match read_dict_file(&input, Some(&dir)) {
            Ok(_) => {
                mismatches.push(format!("{}: parsed without error", input.display()));
                continue;
            }
            Err(e) => e,
        };
        let shown = err.to_string();
        let ok = err.line == line
            && err.col == col
            && err.file.as_deref() == Some(file.as_str())
            && err.message.contains(words)
            && !shown.contains('\n')
            && (line == 0 || shown.starts_with(&format!("{file}:{line}:{col}: ")));
        if !ok {
            mismatches.push(format!(
                "{}: expected {file}:{line}:{col} '{words}', got '{shown}'",
                input.file_name().unwrap().to_string_lossy()
            ));
        }
        if line > 0 {
            let excerpt = err.excerpt().expect("a located error has an excerpt");
            let lines: Vec<&str> = excerpt.lines().collect();
            let caret_line = lines[lines.len() - 1];
            let caret_col = caret_line.find('^').unwrap() - caret_line.find('|').unwrap() - 1;
            let source = lines[lines.len() - 2];
            if source.contains('…') {
                // a long line is shown as a window around the column: the caret stands on
                // a character of it
                let bar = source.chars().position(|c| c == '|').unwrap();
                let under = source.chars().nth(bar + 1 + caret_col);
                assert!(
                    under.is_some_and(|c| c != ' ' && c != '…'),
                    "caret under the column in\n{excerpt}"
                );
            } else {
                assert_eq!(caret_col, col, "caret under the column in\n{excerpt}");
            }
        }
        checked += 1;
    }
    assert!(mismatches.is_empty(), "{mismatches:#?}");
    assert!(checked >= 30, "only {checked} malformed files");
    println!("{checked} malformed files fail at the expected place");
}
