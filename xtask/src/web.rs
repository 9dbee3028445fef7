//! `cargo xtask web`: the playground page (`web/`) built into one folder, served on
//! 127.0.0.1, and tested in Debian's headless chromium (the `web` step of `cargo xtask ci`).

use std::fs;
use std::io::{BufRead as _, BufReader, Read as _, Write as _};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::thread;

use super::{Workspace, run};

/// The wasm-bindgen version of `web/Cargo.toml`: its command-line tool must match it exactly.
const WASM_BINDGEN: &str = "0.2.130";

/// The target the playground's module is built for.
const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// The WebAssembly features the module is built with (rustc's defaults for the target, and
/// `simd128`), as binaryen names them.
const WASM_FEATURES: [&str; 7] = [
    "simd",
    "bulk-memory",
    "sign-ext",
    "nontrapping-float-to-int",
    "mutable-globals",
    "reference-types",
    "multivalue",
];

/// Where Debian puts its chromium.
const CHROMIUM: &str = "/usr/bin/chromium";

/// The seeds and parameters the browser test downloads and compares with the `generate`
/// example's files (`--kind walker --seed 7 --body-scale 1.2`; 2D: `--dim 2d --seed 7`).
const CLI_3D: [&str; 6] = ["--kind", "walker", "--seed", "7", "--body-scale", "1.2"];

/// `cargo xtask web [--serve] [--port N]`.
pub(crate) fn web_task(w: &Workspace, args: &[String]) -> Result<(), String> {
    let mut serve_it = false;
    let mut port = 8000u16;
    let mut rest = args.iter();
    while let Some(a) = rest.next() {
        match a.as_str() {
            "--serve" => serve_it = true,
            "--port" => {
                port = rest
                    .next()
                    .and_then(|p| p.parse().ok())
                    .ok_or("--port needs a port number from 0 to 65535")?;
            }
            other => return Err(format!("unknown web option `{other}`")),
        }
    }
    let site = build(w)?;
    if serve_it {
        let listener = TcpListener::bind(("127.0.0.1", port))
            .map_err(|e| format!("cannot listen on 127.0.0.1:{port}: {e}"))?;
        let address = listener.local_addr().map_err(|e| e.to_string())?;
        println!(
            "serving {} at http://{address}/ (Ctrl-C to stop)",
            site.display()
        );
        serve(&listener, &site);
    }
    Ok(())
}

/// The `web` step of `cargo xtask ci`: builds the page, serves it on an ephemeral port and
/// runs `web/test/browser.mjs` in headless chromium against it.
pub(crate) fn web_ci(w: &Workspace) -> Result<(), String> {
    node_20()?;
    let site = build(w)?;
    let chromium = chromium()?;
    let out = w.root.join("target").join("web").join("cli");
    let _ = fs::remove_dir_all(&out);
    for (args, sub) in [
        (&CLI_3D[..], "3d"),
        (&["--dim", "2d", "--seed", "7"][..], "2d"),
    ] {
        let mut c = w.cargo();
        c.args([
            "run",
            "--locked",
            "--release",
            "-q",
            "-p",
            "creature",
            "--features",
            "libm",
            "--example",
            "generate",
            "--",
        ]);
        c.args(args).arg("--out").arg(out.join(sub));
        run(c)?;
    }
    let listener =
        TcpListener::bind(("127.0.0.1", 0)).map_err(|e| format!("cannot listen: {e}"))?;
    let address = listener.local_addr().map_err(|e| e.to_string())?;
    let served = site.clone();
    thread::spawn(move || serve(&listener, &served));
    let mut c = Command::new("node");
    c.current_dir(w.root.join("web"))
        .arg("test/browser.mjs")
        .arg(format!("http://{address}/"))
        .arg(&out)
        .arg(site.join("pkg").join("creature_web_bg.wasm"))
        .env("CHROMIUM", chromium);
    run(c).map_err(|e| format!("{e}: the browser test failed (its output is above)"))
}

/// Builds the page into `target/web/site` (the module with the `libm` feature in the `web`
/// profile: release with link-time optimisation; wasm's 128-bit SIMD on for the compiler's
/// loops, which leaves every float result as it is) optimised for size by binaryen's
/// `wasm-opt -Os`, wasm-bindgen's JavaScript, three.js, the page's files); returns that folder.
fn build(w: &Workspace) -> Result<PathBuf, String> {
    let mut c = Command::new("rustup");
    c.args(["target", "add", WASM_TARGET]);
    run(c).map_err(|e| format!("{e}: the playground needs the {WASM_TARGET} target"))?;
    let mut c = w.cargo();
    c.args([
        "build",
        "--locked",
        "--profile",
        "web",
        "-p",
        "creature-web",
        "--features",
        "libm",
        "--target",
        WASM_TARGET,
    ]);
    // Added to the caller's flags (cargo takes `CARGO_ENCODED_RUSTFLAGS`, then `RUSTFLAGS`, over
    // a target's own): with `--target`, they reach only the module's build.
    match std::env::var("CARGO_ENCODED_RUSTFLAGS") {
        Ok(flags) if !flags.is_empty() => {
            c.env(
                "CARGO_ENCODED_RUSTFLAGS",
                format!("{flags}\x1f-Ctarget-feature=+simd128"),
            );
        }
        _ => {
            let flags = std::env::var("RUSTFLAGS").unwrap_or_default();
            c.env(
                "RUSTFLAGS",
                format!("{flags} -C target-feature=+simd128").trim_start(),
            );
        }
    }
    run(c)?;
    let bindgen = wasm_bindgen(w)?;
    let site = w.root.join("target").join("web").join("site");
    let _ = fs::remove_dir_all(&site);
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| w.root.join("target"), |t| w.root.join(t));
    let wasm = target
        .join(WASM_TARGET)
        .join("web")
        .join("creature_web.wasm");
    let mut c = Command::new(bindgen);
    c.args(["--target", "web", "--no-typescript", "--out-dir"])
        .arg(site.join("pkg"))
        .arg(&wasm);
    run(c)?;
    let web = w.root.join("web");
    // What the lockfile says, every time (a few seconds: npm keeps its cache).
    let mut c = Command::new("npm");
    c.current_dir(&web).args(["ci", "--no-audit", "--no-fund"]);
    run(c).map_err(|e| {
        format!("{e}: the playground needs npm (Node.js 20 or later) for three.js and binaryen")
    })?;
    // binaryen's `wasm-opt` (from npm, as three.js) optimises the module for size: 517 → 509
    // KB gzipped, no slower. The features are the build's own (the stripped module no longer
    // lists them for it to read).
    let module = site.join("pkg").join("creature_web_bg.wasm");
    let mut c = Command::new(web.join("node_modules").join(".bin").join("wasm-opt"));
    c.arg("-Os")
        .args(WASM_FEATURES.map(|f| format!("--enable-{f}")))
        .arg(&module)
        .arg("-o")
        .arg(&module);
    run(c).map_err(|e| format!("{e}: binaryen's wasm-opt (npm) could not optimise the module"))?;
    let three = web.join("node_modules").join("three");
    let copies = [
        (
            three.join("build/three.module.js"),
            "vendor/three.module.js",
        ),
        (three.join("build/three.core.js"), "vendor/three.core.js"),
        (
            three.join("examples/jsm/controls/OrbitControls.js"),
            "vendor/addons/controls/OrbitControls.js",
        ),
        (three.join("LICENSE"), "vendor/three.LICENSE"),
        (web.join("www/index.html"), "index.html"),
        (web.join("www/main.js"), "main.js"),
        (web.join("www/style.css"), "style.css"),
    ];
    for (from, to) in copies {
        let to = site.join(to);
        if let Some(dir) = to.parent() {
            fs::create_dir_all(dir).map_err(|e| format!("cannot create {dir:?}: {e}"))?;
        }
        fs::copy(&from, &to).map_err(|e| format!("cannot copy {from:?} to {to:?}: {e}"))?;
    }
    let size = fs::metadata(site.join("pkg").join("creature_web_bg.wasm"))
        .map_err(|e| e.to_string())?
        .len();
    println!(
        "web: the page is in {} (creature_web_bg.wasm {:.0} KB)",
        site.display(),
        size as f64 / 1024.0
    );
    Ok(site)
}

/// The `wasm-bindgen` command of version [`WASM_BINDGEN`], installed with cargo when missing.
fn wasm_bindgen(w: &Workspace) -> Result<PathBuf, String> {
    let wanted = format!("wasm-bindgen {WASM_BINDGEN}");
    let installed = |cmd: &Path| {
        Command::new(cmd)
            .arg("--version")
            .output()
            .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == wanted)
    };
    let on_path = PathBuf::from("wasm-bindgen");
    if installed(&on_path) {
        return Ok(on_path);
    }
    let root = w.root.join("target").join("tools");
    let local = root.join("bin").join("wasm-bindgen");
    if !installed(&local) {
        let mut c = w.cargo();
        c.args(["install", "--quiet", "wasm-bindgen-cli", "--version"])
            .arg(format!("={WASM_BINDGEN}"))
            .arg("--root")
            .arg(&root);
        run(c).map_err(|e| format!("{e}: could not install wasm-bindgen-cli {WASM_BINDGEN}"))?;
    }
    Ok(local)
}

/// Checks that `node` is version 20 or later (playwright-core needs it).
fn node_20() -> Result<(), String> {
    let out = Command::new("node")
        .arg("--version")
        .output()
        .map_err(|e| {
            format!("`node` was not found ({e}): the browser test needs Node.js 20 or later")
        })?;
    let version = String::from_utf8_lossy(&out.stdout).trim().to_string();
    let major: u32 = version
        .trim_start_matches('v')
        .split('.')
        .next()
        .and_then(|m| m.parse().ok())
        .unwrap_or(0);
    if major < 20 {
        return Err(format!(
            "node `{version}`: the browser test needs Node.js 20 or later (playwright-core)"
        ));
    }
    Ok(())
}

/// The browser: `$CHROMIUM` when set, else Debian's chromium, installed with apt-get (as
/// root) when missing.
fn chromium() -> Result<PathBuf, String> {
    if let Some(path) = std::env::var_os("CHROMIUM") {
        return Ok(PathBuf::from(path));
    }
    let path = PathBuf::from(CHROMIUM);
    if path.exists() {
        return Ok(path);
    }
    println!("{CHROMIUM} is missing: installing Debian's chromium");
    let mut c = Command::new("apt-get");
    c.arg("update").arg("-qq");
    run(c)?;
    let mut c = Command::new("apt-get");
    c.args(["install", "-y", "-qq", "chromium"])
        .env("DEBIAN_FRONTEND", "noninteractive");
    run(c).map_err(|e| {
        format!("{e}: the browser test needs Debian's chromium (apt-get install chromium, as root)")
    })?;
    Ok(path)
}

/// Serves `site` over HTTP/1.0 on `listener` until the process ends: GET and HEAD of files
/// under it, each connection on a thread of its own.
fn serve(listener: &TcpListener, site: &Path) {
    for stream in listener.incoming().flatten() {
        let site = site.to_path_buf();
        thread::spawn(move || {
            let _ = answer(stream, &site);
        });
    }
}

/// Answers one request on `stream` from the files under `site`.
fn answer(mut stream: TcpStream, site: &Path) -> std::io::Result<()> {
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut line = String::new();
    reader.read_line(&mut line)?;
    // Skip the headers.
    let mut header = String::new();
    while reader.read_line(&mut header)? > 2 {
        header.clear();
    }
    let mut parts = line.split_whitespace();
    let (method, target) = (parts.next().unwrap_or(""), parts.next().unwrap_or("/"));
    let path = target.split(['?', '#']).next().unwrap_or("/");
    let relative = path.trim_start_matches('/');
    let relative = if relative.is_empty() || relative.ends_with('/') {
        format!("{relative}index.html")
    } else {
        relative.to_string()
    };
    let file = (!relative.split('/').any(|p| p == ".." || p.is_empty()))
        .then(|| site.join(&relative))
        .filter(|f| f.is_file());
    let Some(file) = file.filter(|_| method == "GET" || method == "HEAD") else {
        let body = b"not found\n";
        write!(
            stream,
            "HTTP/1.0 404 Not Found\r\nContent-Type: text/plain\r\nContent-Length: {}\r\n\r\n",
            body.len()
        )?;
        return stream.write_all(body);
    };
    let mut body = Vec::new();
    fs::File::open(&file)?.read_to_end(&mut body)?;
    let kind = match file.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("png") => "image/png",
        Some("json") => "application/json",
        _ => "application/octet-stream",
    };
    write!(
        stream,
        "HTTP/1.0 200 OK\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\r\n",
        body.len()
    )?;
    if method == "GET" {
        stream.write_all(&body)?;
    }
    Ok(())
}
