//! Reads a toolpath file and prints what the reader found: the report, the first points and
//! the ranking on the machine's twelve types.
//!
//! `cargo run --release --example read_toolpath -- FILE [MACHINE-JSON]`, MACHINE-JSON an API
//! `machine` object (default: an A/C trunnion, CAZ table-table).

use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{read, Format, ReadOptions};
use fiveaxis::toolpath::{compare_path, Commands, Path};
use nalgebra::Vector3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let file = args
        .get(1)
        .ok_or("usage: read_toolpath FILE [MACHINE-JSON]")?;
    let bytes = std::fs::read(file)?;
    let text = String::from_utf8_lossy(&bytes);
    let machine_json = args.get(2).map_or(
        r#"{"kind":"table-table","type":"CAZ","rotary":{"mFrom":-120,"mTo":30,"kContinuous":true}}"#,
        String::as_str,
    );
    let machine = Machine::from_value(&serde_json::from_str(machine_json)?, "machine")?;
    let format = Format::detect(&text[..text.len().min(65536)]);
    let (points, report) = read(&text, format, Some(&machine), ReadOptions::default())?;
    println!("{}", serde_json::to_string_pretty(&report)?);
    for p in points.iter().take(8) {
        println!(
            "line {:>5} {:?} tip ({:.4}, {:.4}, {:.4}) axis ({:.4}, {:.4}, {:.4}) angles {:?}",
            p.line, p.motion, p.tip.x, p.tip.y, p.tip.z, p.axis.x, p.axis.y, p.axis.z, p.angles
        );
    }
    let axes: Vec<Vector3<f64>> = points.iter().map(|p| p.axis).collect();
    let motions: Vec<_> = points.iter().map(|p| p.motion).collect();
    let angles: Option<Vec<[f64; 2]>> = points.iter().map(|p| p.angles).collect();
    let path = Path {
        axes: &axes,
        motions: Some(&motions),
        commands: angles.as_deref().map(|a| Commands {
            angles: a,
            rtype: machine.rotary_type,
        }),
    };
    if let (Ok(t), true) = (std::env::var("WORST"), points.len() >= 2) {
        let m =
            fiveaxis::toolpath::machine_of_type(&machine, fiveaxis::rotary::RotaryType::parse(&t)?)
                .build()?;
        let a = fiveaxis::toolpath::analyse_path(&m, &path, 100.0, 0.01)?;
        let mut idx: Vec<usize> = (0..a.segments.len())
            .filter(|&i| !a.segments[i].rapid)
            .collect();
        idx.sort_by(|&x, &y| a.segments[y].delta.total_cmp(&a.segments[x].delta));
        for &i in idx.iter().take(6) {
            let (p0, p1) = (&points[i], &points[i + 1]);
            println!(
                "segment {i}: δ {:.4} mm, lines {}→{} {:?}, K {:.3}→{:.3}, M {:.3}→{:.3}",
                a.segments[i].delta,
                p0.line,
                p1.line,
                p1.motion,
                a.following.k[i].to_degrees(),
                a.following.k[i + 1].to_degrees(),
                a.following.m[i].to_degrees(),
                a.following.m[i + 1].to_degrees()
            );
        }
    }
    if points.len() >= 2 {
        let rows = compare_path(
            &machine,
            &path,
            100.0,
            0.01,
            &fiveaxis::rotary::RotaryType::ALL,
        )?;
        for r in rows {
            println!(
                "{:4} max {:>10.4} mm (segment {:>6}) cutting {:>6} rapids {:>4} (max {:.3} mm, swings {}) flips {} commanded {} {}",
                r.rtype.name(),
                r.max,
                r.max_segment,
                r.segments,
                r.rapids.count,
                r.rapids.max,
                r.rapids.swings,
                r.flips,
                r.commanded,
                r.unreachable.map(|u| format!("UNREACHABLE at {}: {}", u.point, u.message)).unwrap_or_default()
            );
        }
    }
    Ok(())
}
