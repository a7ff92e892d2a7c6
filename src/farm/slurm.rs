//! Slurm job scripts: a job array rendering one tile per task, and a merge job that runs
//! after every task succeeded (`--dependency=afterok:ARRAY`, given at submission).

use std::path::{Path, PathBuf};

/// What to submit. Every path is absolute and on a filesystem all nodes share.
#[derive(Clone, Debug, PartialEq)]
pub struct FarmJob {
    /// The `prism` executable the nodes run.
    pub prism: PathBuf,
    /// The scene file.
    pub scene: PathBuf,
    /// Tiles (array tasks).
    pub tiles: u32,
    /// Where tiles, logs and the merged images go.
    pub out_dir: PathBuf,
    /// Name of the merged images (`NAME.exr`, `NAME.png`) and of the jobs.
    pub name: String,
    /// `--partition`.
    pub partition: Option<String>,
    /// `--time` (Slurm's syntax: minutes, `HH:MM:SS`, `D-HH`...).
    pub time: Option<String>,
    /// `--mem` (Slurm's syntax: `4G`, `500M`...).
    pub mem: Option<String>,
    /// Render options appended to every task's command (`--width 64`...), already split.
    pub render_args: Vec<String>,
}

/// `text` quoted for a POSIX shell.
pub fn shell_quote(text: &str) -> String {
    if !text.is_empty() && text.bytes().all(|b| b.is_ascii_alphanumeric() || b"/._-+=:,".contains(&b)) {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}

fn quote_path(path: &Path) -> String {
    shell_quote(&path.to_string_lossy())
}

impl FarmJob {
    fn resources(&self) -> String {
        let mut lines = String::new();
        for (flag, value) in [("partition", &self.partition), ("time", &self.time), ("mem", &self.mem)] {
            if let Some(v) = value {
                lines += &format!("#SBATCH --{flag}={v}\n");
            }
        }
        lines
    }

    /// Where tile `I`'s part file goes (`$I` left to the shell).
    pub fn tile_file(&self, index: &str) -> String {
        format!("{}/tile-{index}.exr", quote_path(&self.out_dir))
    }

    /// The job array: task `I` renders `--tile I/N` into `tile-I.exr`, and is requeued if its
    /// node fails. Re-run single tiles with `sbatch --array=I render.sbatch`.
    pub fn array_script(&self) -> String {
        let n = self.tiles;
        let extra: String = self.render_args.iter().map(|a| format!(" {}", shell_quote(a))).collect();
        format!(
            "#!/bin/bash\n\
             #SBATCH --job-name={name}\n\
             #SBATCH --array=0-{last}\n\
             #SBATCH --requeue\n\
             #SBATCH --output={logs}/tile-%a.log\n\
             {resources}\
             # One tile of {n} per task; Slurm's array index is 0-based, as --tile's.\n\
             set -euo pipefail\n\
             exec {prism} render {scene} --tile \"${{SLURM_ARRAY_TASK_ID}}/{n}\"{extra} --exr {out}\n",
            name = shell_quote(&self.name),
            last = n - 1,
            logs = quote_path(&self.out_dir),
            resources = self.resources(),
            prism = quote_path(&self.prism),
            scene = quote_path(&self.scene),
            out = self.tile_file("\"${SLURM_ARRAY_TASK_ID}\""),
        )
    }

    /// The merge job: every tile into `NAME.exr` and `NAME.png`. Submitted with
    /// `--dependency=afterok:ARRAY`; if tiles are missing it fails naming them.
    pub fn merge_script(&self) -> String {
        format!(
            "#!/bin/bash\n\
             #SBATCH --job-name={name}-merge\n\
             #SBATCH --output={dir}/merge.log\n\
             {resources}\
             set -euo pipefail\n\
             shopt -s nullglob\n\
             exec {prism} merge -o {dir}/{name}.exr -o {dir}/{name}.png {tiles}\n",
            name = shell_quote(&self.name),
            dir = quote_path(&self.out_dir),
            resources = self.resources(),
            prism = quote_path(&self.prism),
            tiles = self.tile_file("*"),
        )
    }
}

/// The job id `sbatch --parsable` printed (`ID` or `ID;CLUSTER`).
pub fn parse_job_id(output: &str) -> Option<u64> {
    output.trim().split(';').next()?.trim().parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job() -> FarmJob {
        FarmJob {
            prism: "/opt/prism/bin/prism".into(),
            scene: "/shared/scenes/my room.toml".into(),
            tiles: 8,
            out_dir: "/shared/out".into(),
            name: "room".into(),
            partition: Some("gpu".into()),
            time: Some("01:00:00".into()),
            mem: None,
            render_args: vec!["--samples".into(), "64".into()],
        }
    }

    #[test]
    fn the_array_renders_one_tile_per_task() {
        let script = job().array_script();
        for line in [
            "#SBATCH --array=0-7\n",
            "#SBATCH --requeue\n",
            "#SBATCH --partition=gpu\n",
            "#SBATCH --time=01:00:00\n",
            "exec /opt/prism/bin/prism render '/shared/scenes/my room.toml' --tile \"${SLURM_ARRAY_TASK_ID}/8\" --samples 64 --exr /shared/out/tile-\"${SLURM_ARRAY_TASK_ID}\".exr\n",
        ] {
            assert!(script.contains(line), "{line} not in\n{script}");
        }
        assert!(!script.contains("--mem"));
        let merge = job().merge_script();
        assert!(
            merge.contains("merge -o /shared/out/room.exr -o /shared/out/room.png /shared/out/tile-*.exr"),
            "{merge}"
        );
    }

    #[test]
    fn quoting_and_job_ids() {
        assert_eq!(shell_quote("it's"), r"'it'\''s'");
        assert_eq!(shell_quote(""), "''");
        assert_eq!(shell_quote("$(rm -rf /)"), "'$(rm -rf /)'");
        assert_eq!(parse_job_id("1234\n"), Some(1234));
        assert_eq!(parse_job_id("99;cluster"), Some(99));
        assert_eq!(parse_job_id("Submitted batch job 5"), None);
    }
}
