//! `basr simulate` on small inputs must end and never panic: the first byte
//! picks a robot description (TOML text, simulating a short synthetic job
//! sealed for it) or a job (JSON, simulated when `basr check` passes it and
//! it has at most 400 rows, as the command would).
#![no_main]
use basr_sim as sim;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let job = if mode % 2 == 0 {
        let Ok(robot) = basr_robot::Robot::from_toml_str(text, "fuzz") else {
            return;
        };
        let mut job = sim::synthetic::retracted_then_extending_job();
        job.robot = basr_robot::AnyRobot::Basr(robot);
        job.seal();
        job
    } else {
        let Ok(job) = basr_job::Job::from_str_verified(text, "fuzz") else {
            return;
        };
        if job.samples.len() > 400 || !basr_job::verify::problems(&job, "fuzz").is_empty() {
            return;
        }
        job
    };
    let Ok(model) = sim::SimModel::from_robot(&job.robot) else {
        return;
    };
    let _ = sim::simulate(&job, &model, &sim::Options::default(), &mut |_, _| {});
});
