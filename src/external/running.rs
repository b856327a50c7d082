//! One run of an external controller: the handshake, the `run` message, then a `step` per step
//! with every reply checked (its type, its step number, its character count, finite numbers)
//! before anything is recorded. The first failure stops the backend: it kills the process and
//! keeps the message for the runner ([`Backend::failure`]).

use std::time::Duration;

use glam::Vec2;

use super::config::{ControllerFile, Mode};
use super::process::{Failure, Process};
use super::protocol::{
    self, CharacterMessage, ConfigMessage, InputMessage, Reply, Request, RunRequest, StateReply,
    StepCharacter, StepRequest,
};
use super::ExternalSettings;
use crate::backend::{Backend, BackendError, CharacterId, CharacterSpec, CharacterState};
use crate::level::{Level, Platform};
use crate::motion::{Contacts, Input, MotionParams, MotionState};

/// What the handshake told.
pub(super) struct Hello {
    pub(super) name: String,
    pub(super) description: String,
    pub(super) configs: Vec<ConfigMessage>,
}

/// At most this much of a bad line goes into an error message.
const QUOTED: usize = 120;

/// `line` shortened for an error message.
fn quote(line: &str) -> String {
    let line = line.trim_end();
    match line.char_indices().nth(QUOTED) {
        Some((cut, _)) => format!("{:?}...", &line[..cut]),
        None => format!("{line:?}"),
    }
}

/// The next reply, parsed.
fn reply(process: &mut Process, timeout: Duration) -> Result<Reply, Failure> {
    let line = process.receive(timeout)?;
    serde_json::from_str(&line).map_err(|e| {
        format!(
            "it printed {} where a reply was due ({e}){}",
            quote(&line),
            process.tails()
        )
    })
}

/// Sends `hello` and reads the answer.
fn hello(process: &mut Process, file: &ControllerFile) -> Result<Hello, Failure> {
    process.send(&Request::Hello {
        protocol: protocol::VERSION,
        mode: file.mode.label(),
    })?;
    match reply(process, file.start_timeout)? {
        Reply::Hello {
            protocol,
            name,
            description,
            configs,
        } => {
            if protocol != protocol::VERSION {
                return Err(format!(
                    "it speaks protocol {protocol}; this platbench speaks {}",
                    protocol::VERSION
                ));
            }
            Ok(Hello {
                name,
                description,
                configs,
            })
        }
        other => Err(format!("it answered hello with {other:?}")),
    }
}

/// Starts the controller of `file`, reads its handshake and ends it.
pub(super) fn handshake(file: &ControllerFile) -> Result<Hello, Failure> {
    let mut process = Process::start(file)?;
    let h = hello(&mut process, file)?;
    process.send(&Request::End)?;
    process.finish(file.step_timeout);
    Ok(h)
}

/// A running external controller.
pub(super) struct Running {
    name: &'static str,
    mode: Mode,
    timeout: Duration,
    process: Process,
    params: MotionParams,
    platforms: Vec<Platform>,
    /// Each character's shared motion (collision mode) and last state.
    characters: Vec<(MotionState, CharacterState)>,
    request: StepRequest,
    ns: f64,
    failed: Option<String>,
}

/// Starts the controller for one run of `settings` over `level`.
pub(super) fn start(
    settings: &ExternalSettings,
    level: &Level,
    params: &MotionParams,
    characters: &[CharacterSpec],
) -> Result<Running, BackendError> {
    let file = &*settings.file;
    let external = |message: Failure| BackendError::External {
        backend: settings.name,
        message,
    };
    let mut process = Process::start(file).map_err(external)?;
    hello(&mut process, file).map_err(external)?;
    let pair = |v: Vec2| [v.x, v.y];
    process
        .send(&Request::Run(Box::new(RunRequest {
            config: &settings.label,
            level: protocol::level_message(level),
            params: params.into(),
            characters: characters
                .iter()
                .map(|c| CharacterMessage {
                    spawn: pair(c.spawn),
                    size: pair(c.size),
                    velocity: pair(c.velocity),
                    shape: settings.shape.label(),
                })
                .collect(),
        })))
        .map_err(external)?;
    match reply(&mut process, file.start_timeout).map_err(external)? {
        Reply::Ready => {}
        Reply::Refuse { reason } => {
            return Err(BackendError::Unsupported {
                backend: settings.name,
                feature: format!("this level (it refuses it: {reason})"),
                level: level.name.clone(),
                beyond_bound: false,
            })
        }
        other => return Err(external(format!("it answered run with {other:?}"))),
    }
    Ok(Running {
        name: settings.name,
        mode: file.mode,
        timeout: file.step_timeout,
        process,
        params: params.clone(),
        platforms: level.platforms.clone(),
        characters: characters
            .iter()
            .map(|c| {
                (
                    MotionState::with_velocity(c.velocity),
                    CharacterState {
                        pos: c.spawn,
                        vel: c.velocity,
                        ..Default::default()
                    },
                )
            })
            .collect(),
        request: StepRequest {
            characters: vec![StepCharacter::default(); characters.len()],
            platforms: vec![[0.0; 2]; level.platforms.len()],
            ..Default::default()
        },
        ns: 0.0,
        failed: None,
    })
}

impl Running {
    /// One step, or why it failed.
    fn try_step(&mut self, inputs: &[Input], dt: f32) -> Result<(), Failure> {
        let r = &mut self.request;
        r.time = (r.step + 1) as f64 * dt as f64;
        r.dt = dt;
        for (k, ((motion, _), c)) in self
            .characters
            .iter_mut()
            .zip(r.characters.iter_mut())
            .enumerate()
        {
            let input = inputs.get(k).copied().unwrap_or_default();
            c.input = InputMessage::from(&input);
            if self.mode == Mode::Collision {
                motion.integrate(&self.params, &input, dt);
                c.desired = Some([motion.vel.x, motion.vel.y]);
                c.drop_through = motion.drop_through;
            }
        }
        for (p, at) in self.platforms.iter().zip(r.platforms.iter_mut()) {
            let v = p.position(r.time);
            *at = [v.x, v.y];
        }
        self.process.send(&Request::Step(&self.request))?;
        let state = match reply(&mut self.process, self.timeout)? {
            Reply::State(s) => s,
            other => return Err(format!("it answered a step with {other:?}")),
        };
        // Its last stderr lines often say why (a script error before a short reply).
        self.check(&state)
            .map_err(|e| format!("{e}{}", self.process.tails()))?;
        for (k, ((motion, out), c)) in self
            .characters
            .iter_mut()
            .zip(&state.characters)
            .enumerate()
        {
            let input = inputs.get(k).copied().unwrap_or_default();
            let vel = match self.mode {
                Mode::Collision => {
                    let contacts = Contacts {
                        wall: c.wall,
                        ground: c.grounded,
                        ceiling: c.ceiling,
                        one_way: c.on_one_way,
                    };
                    motion.apply_contacts(&self.params, &input, contacts);
                    motion.on_ladder = c.ladder;
                    motion.vel
                }
                Mode::Whole => Vec2::from(c.velocity),
            };
            *out = CharacterState {
                pos: Vec2::from(c.position),
                vel,
                grounded: c.grounded,
                ground_normal: Vec2::from(c.ground_normal),
                platform: c.platform,
                ladder: c.ladder,
                crushed: c.crushed,
            };
        }
        self.ns += state.ns;
        self.request.step += 1;
        Ok(())
    }

    /// Refuses a reply to the wrong step, for another number of characters, or with a number
    /// that is not finite.
    fn check(&self, state: &StateReply) -> Result<(), Failure> {
        let step = self.request.step;
        if state.step != step {
            return Err(format!(
                "it replied to step {} when step {step} was asked (out of order)",
                state.step
            ));
        }
        if state.characters.len() != self.characters.len() {
            return Err(format!(
                "it replied with {} characters; the run has {}",
                state.characters.len(),
                self.characters.len()
            ));
        }
        if let Some(k) = state.characters.iter().position(|c| !c.is_finite()) {
            return Err(format!(
                "character {k}'s state is not finite: {:?}",
                state.characters[k]
            ));
        }
        if let Some(k) = state.characters.iter().position(|c| {
            c.platform
                .is_some_and(|p| p as usize >= self.platforms.len())
        }) {
            return Err(format!(
                "character {k} rides platform {:?}; the level has {}",
                state.characters[k].platform,
                self.platforms.len()
            ));
        }
        if !(state.ns.is_finite() && state.ns >= 0.0) {
            return Err(format!(
                "its step time {} ns is not a finite time of 0 or more",
                state.ns
            ));
        }
        Ok(())
    }
}

impl Backend for Running {
    fn name(&self) -> &'static str {
        self.name
    }
    fn step(&mut self, inputs: &[Input], dt: f32) {
        if self.failed.is_some() {
            return;
        }
        if let Err(e) = self.try_step(inputs, dt) {
            self.failed = Some(format!("controller step {}: {e}", self.request.step));
            self.process.finish(Duration::ZERO);
        }
    }
    fn state(&self, id: CharacterId) -> CharacterState {
        self.characters
            .get(id)
            .map_or_else(CharacterState::default, |c| c.1)
    }
    fn failure(&self) -> Option<String> {
        self.failed.clone()
    }
    fn reported_ns(&self) -> Option<f64> {
        Some(self.ns)
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        if self.failed.is_none() {
            let _ = self.process.send(&Request::End);
            self.process
                .finish(self.timeout.min(Duration::from_millis(200)));
        }
    }
}
