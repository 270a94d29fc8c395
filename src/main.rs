//! The `rasterlab` command: parses arguments (`app::cli`) and calls the library.

use clap::{CommandFactory, FromArgMatches};
use rasterlab::app::cli::{
    CheckArgs, CheckRows, Cli, Command, Explain, Failure, OutputGroup, Parts, StageOptions,
};
use rasterlab::app::streams::printable;
use rasterlab::app::{self, check, explain, viewer};
use rasterlab::measure::raytrace;
use rasterlab::say;
use rasterlab::StageName;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// A stage subcommand: the figure written to `-o` (or its default name).
fn render(
    stage: StageName,
    output: &OutputGroup,
    buffer: bool,
    parts: Parts,
) -> Result<(), Failure> {
    let figure = parts.figure(stage)?;
    let out = output.out.clone().unwrap_or_else(|| {
        let name = figure.default_file();
        PathBuf::from(match buffer {
            true => name.replace(".png", "-buffer.png"),
            false => name,
        })
    });
    let (scene, settings) = parts.resolve()?;
    let runs = output.time.map(|n| n as usize);
    let (timing, stats) =
        app::render_to_file(figure, scene.model(), &settings, &out, runs, buffer)?;
    if let Some(t) = timing {
        say!("render: {t}");
    }
    if parts.raster.is_some_and(|r| r.stats) {
        say!("{}", app::stats_text(&stats).trim_end());
    }
    say!("wrote {}", app::image_io::describe(&out));
    Ok(())
}

/// `rasterlab check`: a screenshot, or with `rows` a rows printout.
fn check(a: &CheckArgs) -> Result<(), Failure> {
    use check::CheckError;
    // In the spirit of diff and cmp: 0 the handout's, 1 different, 2 trouble.
    let failure = |e: CheckError| match e {
        CheckError::Usage(m) => Failure::Usage(m),
        CheckError::Run(m) => Failure::Trouble(m),
    };
    if let Some(CheckRows::Rows(r)) = &a.rows {
        let result = check::check_rows_file(&r.file, &r.vertices).map_err(failure)?;
        match r.json {
            true => print_out(&format!("{}\n", result.json(&r.file.display().to_string())))?,
            false => print_out(&result.text())?,
        }
        return match result.is_handouts() {
            true => Ok(()),
            false => Err(Failure::Differs),
        };
    }
    let options = a.options();
    let single = match a.images.as_slice() {
        [one] if !one.is_dir() => Some(one),
        _ => None,
    };
    let Some(image) = single else {
        let mut progress = app::progress::Progress::on_stderr();
        let (checks, table) =
            check::check_many(&a.images, &options, a.json, a.csv.as_deref(), &mut progress)
                .map_err(failure)?;
        print_out(&table)?;
        let written = a.csv.iter().chain(checks.iter().flat_map(|c| &c.written));
        written.for_each(|path| say!("wrote {}", app::image_io::describe(path)));
        return match checks.iter().all(|c| c.status == check::Status::Matches) {
            true => Ok(()),
            false => Err(Failure::Differs),
        };
    };
    if a.csv.is_some() {
        return Err(Failure::Usage(
            "--csv writes the table of several files or a folder; give it those".into(),
        ));
    }
    if options.fit_light {
        let what = format!("{}: fitting the light, about 2 s", image.display());
        app::progress::Progress::on_stderr().note(&what);
    }
    let (result, written) = check::check_image_file(image, &options).map_err(failure)?;
    let name = image.display().to_string();
    match a.json {
        true => print_out(&format!("{}\n", result.json(&name)))?,
        false => print_out(&result.text(&name))?,
    }
    for path in written {
        say!("wrote {}", app::image_io::describe(&path));
    }
    match result.is_handouts_figure(a.stage) {
        true => Ok(()),
        false => Err(Failure::Differs),
    }
}

/// Prints to standard output; a reader that has gone away (`| head`) ends the
/// output quietly.
fn print_out(text: &str) -> Result<(), Failure> {
    Ok(app::image_io::write_bytes(Path::new("-"), text.as_bytes())?)
}

fn wrote(paths: Vec<PathBuf>) {
    for path in paths {
        say!("wrote {}", app::image_io::describe(&path));
    }
}

fn run(cli: Cli) -> Result<(), Failure> {
    match &cli.command {
        Command::Points(a) => render(StageName::Points, &a.output, false, a.options.parts()),
        Command::Wireframe(a) => render(StageName::Wireframe, &a.output, false, a.options.parts()),
        Command::Filled(a) => render(StageName::Filled, &a.output, false, a.options.parts()),
        Command::Depth(a) => render(StageName::Depth, &a.output, a.buffer, a.options.parts()),
        Command::VertexLight(a) => render(
            StageName::VertexLight,
            &a.output,
            a.buffer,
            a.options.parts(),
        ),
        Command::PixelLight(a) => render(
            StageName::PixelLight,
            &a.output,
            a.buffer,
            a.options.parts(),
        ),
        Command::All(a) => {
            let (scene, settings) = a.parts().resolve()?;
            wrote(app::render_all(scene.model(), &settings, &a.out)?);
            Ok(())
        }
        Command::Raytrace(a) => {
            let (scene, settings) = a.parts().resolve()?;
            let options = raytrace::Options {
                shading: match a.flat {
                    true => raytrace::Shading::Flat,
                    false => raytrace::Shading::Lit,
                },
                shadows: a.shadows,
                samples: a.samples,
                filter: settings.filter,
                ..raytrace::Options::default()
            };
            let out = a
                .output
                .out
                .clone()
                .unwrap_or_else(|| "raytrace.png".into());
            let runs = a.output.time.map(|n| n as usize);
            let timing = app::raytrace_to_file(scene.model(), &settings, &options, &out, runs)?;
            if let Some(t) = timing {
                say!("render: {t}");
            }
            say!("wrote {}", app::image_io::describe(&out));
            Ok(())
        }
        Command::Report(a) => {
            let scene = app::cli::load_scene(&a.scene)?;
            let mut view = rasterlab::app::report::view_for(&scene)?;
            view.light.position = a.light.unwrap_or(view.light.position);
            if let Some(power) = a.light_power {
                view.light.power = glam::Vec3::splat(power);
            }
            let mut progress = app::progress::Progress::on_stderr();
            wrote(app::report(&a.out, a.quick, &scene, &view, &mut progress)?);
            Ok(())
        }
        Command::Stress(a) => {
            app::stress_fits(a.quick)?;
            let (tables, failed, total) =
                app::stress(a.quick, &mut app::progress::Progress::on_stderr());
            print_out(&format!("{tables}\n"))?;
            match failed {
                0 => Ok(()),
                _ => Err(format!("{failed} of {total} stress cases failed").into()),
            }
        }
        Command::View(a) => {
            let parts = a.options.parts();
            let (scene, settings) = parts.resolve()?;
            let options = viewer::Options {
                settings,
                model: scene,
                scene: parts.scene.scene.clone(),
                texture: parts.texture.and_then(|t| t.texture.clone()),
                normal_map: parts.normal_map.map(str::to_string),
                view: parts.figure(a.stage)?,
                frames: a.frames,
                screenshot: a.screenshot.clone(),
                script: a.keys.clone().unwrap_or_default().0,
                fps: a.fps as usize,
            };
            let summary = viewer::run(options)?;
            say!(
                "view: {} frames, frame time median {:.2} ms, draw median {:.2} ms",
                summary.frames,
                summary.frame_median.as_secs_f64() * 1e3,
                summary.draw_median.as_secs_f64() * 1e3
            );
            say!("view: last frame: {}", summary.reproduce());
            Ok(())
        }
        Command::Export(a) => {
            let scene = app::cli::load_scene(&a.scene)?;
            if scene.maps.any(&scene.mesh, |m| m.texture) {
                say!("warning: the scene's textures are not written: its .mtl gives each material its Kd only");
            }
            app::export_obj(&scene.mesh, &a.out)?;
            let n = scene.mesh.faces.len();
            say!(
                "wrote {} and its .mtl ({n} triangles)",
                app::image_io::describe(&a.out)
            );
            Ok(())
        }
        Command::Animate(a) => {
            let (stage, parts) = a.stage.parts();
            let figure = parts.figure(stage)?;
            let name = figure.default_file().replace(".png", ".gif");
            let out = a.out.clone().unwrap_or_else(|| PathBuf::from(name));
            let (scene, settings) = parts.resolve()?;
            let (w, h) = (settings.camera.width, settings.camera.height);
            app::animation_size(w, h).map_err(Failure::Usage)?;
            let delay = a.delay as u32;
            let frames = app::animate_to_file(figure, scene.model(), &settings, &out, delay)?;
            say!("wrote {} ({frames} frames)", app::image_io::describe(&out));
            Ok(())
        }
        Command::Explain(e) => {
            let (picture, out, default) = match e {
                Explain::Line(a) => (explain::explain_line(a.a, a.b), &a.out, "explain-line.png"),
                Explain::Bresenham(a) => (
                    explain::explain_bresenham(a.a, a.b),
                    &a.out,
                    "explain-bresenham.png",
                ),
                Explain::Rows(a) => (
                    explain::explain_rows(&a.vertices),
                    &a.out,
                    "explain-rows.png",
                ),
                Explain::Edge(a) => {
                    let c = [a.corners[0], a.corners[1], a.corners[2]];
                    (explain::explain_edge(&c), &a.out, "explain-edge.png")
                }
                Explain::Shared(a) => {
                    let c = [a.corners[0], a.corners[1], a.corners[2], a.corners[3]];
                    (explain::explain_shared(&c), &a.out, "explain-shared.png")
                }
            };
            let out = out.clone().unwrap_or_else(|| PathBuf::from(default));
            let frame = picture.map_err(Failure::Usage)?;
            app::image_io::write_image(&frame, &out)?;
            say!("wrote {}", app::image_io::describe(&out));
            Ok(())
        }
        Command::Check(a) => check(a),
        Command::Rows(a) => print_out(&app::rows_text(&a.vertices)),
    }
}

fn main() -> ExitCode {
    app::streams::write_errors_not_signals();
    app::image_io::remove_temporaries_on_signals();
    let cli = match Cli::command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // Plain `rasterlab`: the help, but as the usage error it is.
            let _ = e.print();
            return ExitCode::from(2);
        }
        Err(e) if !e.use_stderr() => {
            // --help and --version: clap prints them in full, on stdout.
            return match e.print().is_ok() {
                true => ExitCode::SUCCESS,
                false => ExitCode::from(1),
            };
        }
        Err(e) => {
            say!(
                "{} (see 'rasterlab --help')",
                printable(&app::cli::one_line(&e))
            );
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            say!("error: {} (see 'rasterlab --help')", printable(&message));
            ExitCode::from(2)
        }
        Err(Failure::Run(message)) => {
            say!("error: {}", printable(&message));
            ExitCode::from(1)
        }
        Err(Failure::ClosedEarly | Failure::Differs) => ExitCode::from(1),
        Err(Failure::Trouble(message)) => {
            say!("error: {}", printable(&message));
            ExitCode::from(2)
        }
    }
}
