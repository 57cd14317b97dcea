//! `detach explore`: the local page of [`detach::explore`], its URL
//! printed and opened in a browser.

use super::{CliError, CliResult};
use detach::explore::{Config, Explorer};
use std::net::IpAddr;

#[derive(clap::Args, Debug)]
pub struct ExploreArgs {
    /// The scene shown first: viscous-disc, smooth-disc, ice-disc or
    /// painleve-rod (the default).
    #[arg(long, conflicts_with = "scene_file")]
    pub scene: Option<String>,
    /// A scene file (TOML) shown first, its text in the page's editor.
    #[arg(long = "scene-file", value_name = "FILE")]
    pub scene_file: Option<std::path::PathBuf>,
    /// The port to serve on; 0 (the default) takes a free one.
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// Serve on this address instead of 127.0.0.1. Anyone who can reach it
    /// and learns the URL's token can run computations on this machine.
    #[arg(long, value_name = "ADDR")]
    pub host: Option<IpAddr>,
    /// Print the URL without opening a browser.
    #[arg(long)]
    pub no_browser: bool,
}

pub fn run_explore(args: &ExploreArgs) -> CliResult {
    let mut config = Config::default();
    if let Some(name) = &args.scene {
        config.scene = Some(name.clone());
    }
    if let Some(path) = &args.scene_file {
        let text =
            detach::scene::SceneText::read(path).map_err(|e| CliError::usage(e.to_string()))?;
        config.scene = None;
        config.scene_text = Some(text.text.to_string());
    }
    if let Some(ip) = args.host {
        if !ip.is_loopback() {
            eprintln!(
                "detach: warning: serving on {ip}, not loopback: anyone who can reach it \
                 and learns the token can use this page"
            );
        }
        config.ip = ip;
    }
    config.port = args.port;
    let explorer = Explorer::start(config)?;
    // The URL on stdout (scripts read it); the rest on stderr.
    outln!("{}", explorer.url);
    super::stdout_status()?;
    eprintln!("detach explore: serving the page above; Ctrl+C stops");
    if !args.no_browser {
        open_browser(&explorer.url);
    }
    explorer.wait();
    Ok(())
}

/// Opens `url` in the desktop's browser, if there is one; the URL is
/// printed either way.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    let spawned = std::process::Command::new(opener)
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if spawned.is_err() {
        eprintln!("detach explore: no browser opened ({opener} not found); open the URL above");
    }
}
