//! The example building (examples/building/) through a real single-node Slurm: its
//! submit script runs the rooms as a job array (`sbatch --array`, one shard a task) and chains
//! the merge with `--dependency=afterok`; the controllers' bases must equal a local build's
//! byte for byte.
//!
//! The test starts its own munge and Slurm daemons (as root, in a scratch folder, on ports of
//! their own; the configuration of docs/building.md, "Slurm") and stops them, by their
//! process ids, when it ends. Without root or without Debian's `slurm-wlm` and `munge` it
//! prints `SKIPPED: <why>` and passes; `scripts/test.sh` installs them.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use eigenrad_precompute::building::{self, Manifest};
use eigenrad_precompute::pipeline::BuildOptions;

/// Longest wait for the node to come up, and for the jobs to finish.
const NODE_UP: Duration = Duration::from_secs(60);
const JOBS_DONE: Duration = Duration::from_secs(900);

/// The daemons the test started, stopped by their ids when it ends (also on a panic).
struct Daemons(Vec<Child>);

impl Drop for Daemons {
    fn drop(&mut self) {
        for child in self.0.iter_mut().rev() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// The program's path, looked up in the PATH and in the administrator's folders.
fn program(name: &str) -> Option<PathBuf> {
    let path = std::env::var("PATH").unwrap_or_default();
    path.split(':')
        .map(PathBuf::from)
        .chain(["/usr/sbin", "/sbin", "/usr/bin"].map(PathBuf::from))
        .map(|dir| dir.join(name))
        .find(|p| p.is_file())
}

fn is_root() -> bool {
    std::fs::read_to_string("/proc/self/status").is_ok_and(|s| {
        s.lines()
            .find(|l| l.starts_with("Uid:"))
            .is_some_and(|l| l.split_whitespace().nth(1) == Some("0"))
    })
}

/// Why Slurm cannot run here, if it cannot.
fn unavailable() -> Option<String> {
    if !is_root() {
        return Some("the single-node Slurm needs root".into());
    }
    let missing: Vec<&str> = [
        "munged",
        "mungekey",
        "slurmctld",
        "slurmd",
        "sbatch",
        "squeue",
        "sinfo",
    ]
    .into_iter()
    .filter(|p| program(p).is_none())
    .collect();
    (!missing.is_empty()).then(|| {
        format!(
            "{} not installed (apt-get install slurm-wlm munge)",
            missing.join(", ")
        )
    })
}

fn spawn(program_name: &str, args: &[&str], log: &Path, conf: &Path) -> Child {
    let log = std::fs::File::create(log).expect("daemon log");
    Command::new(program(program_name).expect("checked"))
        .args(args)
        .env("SLURM_CONF", conf)
        .stdin(Stdio::null())
        .stdout(log.try_clone().expect("log"))
        .stderr(log)
        .spawn()
        .unwrap_or_else(|e| panic!("start {program_name}: {e}"))
}

fn output(command: &mut Command) -> String {
    let o = command.output().expect("run");
    assert!(
        o.status.success(),
        "{command:?} failed: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn first_line(text: &str) -> String {
    text.lines().next().unwrap_or("").trim().to_string()
}

/// Starts munge and a one-node Slurm in `dir`; returns them and the configuration's path.
fn start_slurm(dir: &Path) -> (Daemons, PathBuf) {
    let key = dir.join("munge.key");
    output(
        Command::new(program("mungekey").expect("checked"))
            .args(["-c", "-k"])
            .arg(&key),
    );
    let socket = dir.join("munge.sock");
    let conf = dir.join("slurm.conf");
    let mut daemons = Daemons(Vec::new());
    let arg = |flag: &str, p: &Path| format!("{flag}={}", p.display());
    daemons.0.push(spawn(
        "munged",
        &[
            "--foreground",
            "--force",
            &arg("--key-file", &key),
            &arg("--socket", &socket),
            &arg("--pid-file", &dir.join("munged.pid")),
            &arg("--seed-file", &dir.join("munged.seed")),
            &arg("--log-file", &dir.join("munged.log")),
        ],
        &dir.join("munged.out"),
        &conf,
    ));
    let host = first_line(&output(Command::new("hostname").arg("-s")));
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    let memory_mb = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|m| {
            m.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(1024, |kb| kb / 1024 / 2);
    for sub in ["ctld", "d"] {
        std::fs::create_dir_all(dir.join(sub)).expect("spool folder");
    }
    let d = dir.display();
    std::fs::write(
        &conf,
        format!(
            "ClusterName=eigenradtest\nSlurmctldHost={host}\nSlurmUser=root\nSlurmdUser=root\n\
             AuthType=auth/munge\nAuthInfo=socket={d}/munge.sock\nCredType=cred/munge\n\
             ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n\
             SchedulerType=sched/backfill\nSelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n\
             StateSaveLocation={d}/ctld\nSlurmdSpoolDir={d}/d\n\
             SlurmctldPidFile={d}/slurmctld.pid\nSlurmdPidFile={d}/slurmd.pid\n\
             SlurmctldPort=16817\nSlurmdPort=16818\nReturnToService=2\n\
             JobAcctGatherType=jobacct_gather/none\n\
             NodeName={host} CPUs={cpus} RealMemory={memory_mb} State=UNKNOWN\n\
             PartitionName=main Nodes={host} Default=YES MaxTime=INFINITE State=UP\n"
        ),
    )
    .expect("slurm.conf");
    // munged must be answering before the Slurm daemons authenticate.
    std::thread::sleep(Duration::from_secs(1));
    let conf_arg = conf.to_string_lossy().into_owned();
    daemons.0.push(spawn(
        "slurmctld",
        &["-D", "-f", &conf_arg],
        &dir.join("slurmctld.log"),
        &conf,
    ));
    daemons.0.push(spawn(
        "slurmd",
        &["-D", "-f", &conf_arg],
        &dir.join("slurmd.log"),
        &conf,
    ));
    let start = Instant::now();
    loop {
        let state = Command::new(program("sinfo").expect("checked"))
            .args(["-h", "-o", "%T"])
            .env("SLURM_CONF", &conf)
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
            .unwrap_or_default();
        if state.trim() == "idle" {
            break;
        }
        let log = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap_or_default();
        assert!(
            start.elapsed() < NODE_UP,
            "the Slurm node is not idle after {NODE_UP:?} (sinfo: {state:?})\nslurmctld:\n{}\nslurmd:\n{}",
            log("slurmctld.log"),
            log("slurmd.log")
        );
        std::thread::sleep(Duration::from_millis(500));
    }
    (daemons, conf)
}

/// The bases (`*.basis`) in `dir`, by file name, with their bytes.
fn bases(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut found: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .expect("output folder")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "basis"))
        .map(|p| {
            let name = p.file_name().expect("file").to_string_lossy().into_owned();
            (name, std::fs::read(&p).expect("basis"))
        })
        .collect();
    found.sort();
    found
}

#[test]
fn example_building_through_slurm_equals_the_local_build() {
    if let Some(why) = unavailable() {
        println!("SKIPPED: {why}");
        return;
    }
    let dir = common::scratch("slurm");
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/building/building.toml");
    let eigenrad = common::eigenrad();
    // The local build in this process (the test profile is optimised; the jobs run the
    // `eigenrad` binary): every room at once, then the merge.
    let local = dir.join("local");
    let loaded = Manifest::load(&manifest).unwrap_or_else(|e| panic!("{e}"));
    let parts = building::parts_dir(&local);
    std::fs::create_dir_all(&parts).expect("parts folder");
    let all: Vec<usize> = (0..loaded.rooms.len()).collect();
    building::build_rooms(&loaded, &all, &BuildOptions::default(), &parts)
        .unwrap_or_else(|e| panic!("{e}"));
    building::merge(&loaded, &parts, &local, loaded.flash).unwrap_or_else(|e| panic!("{e}"));
    let (daemons, conf) = start_slurm(&dir);
    let cluster = dir.join("cluster");
    let submit = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/building/slurm/submit.sh");
    let ids = output(
        Command::new(&submit)
            .arg(&manifest)
            .arg(&cluster)
            .arg("4")
            .env("SLURM_CONF", &conf)
            .env("EIGENRAD", eigenrad)
            .env("EIGENRAD_CACHE_DIR", dir.join("cache")),
    );
    let ids: Vec<String> = ids.split_whitespace().map(str::to_string).collect();
    assert_eq!(
        ids.len(),
        2,
        "submit.sh prints the array's and the merge's job ids"
    );
    let start = Instant::now();
    loop {
        let queued = output(
            Command::new(program("squeue").expect("checked"))
                .args(["-h", "-j", &ids.join(",")])
                .env("SLURM_CONF", &conf),
        );
        if queued.trim().is_empty() {
            break;
        }
        assert!(
            start.elapsed() < JOBS_DONE,
            "jobs still queued after {JOBS_DONE:?}:\n{queued}"
        );
        std::thread::sleep(Duration::from_secs(1));
    }
    drop(daemons);
    let logs = || {
        std::fs::read_dir(cluster.join("logs"))
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| {
                format!(
                    "{}:\n{}",
                    e.path().display(),
                    std::fs::read_to_string(e.path()).unwrap_or_default()
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let (expected, found) = (bases(&local), bases(&cluster));
    assert_eq!(
        expected.len(),
        7,
        "the example building has seven controllers"
    );
    let names = |b: &[(String, Vec<u8>)]| b.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&found),
        names(&expected),
        "the merge through Slurm wrote other bases; logs:\n{}",
        logs()
    );
    for ((name, a), (_, b)) in expected.iter().zip(&found) {
        assert!(
            a == b,
            "{name}: the basis through Slurm differs from the local build's"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
