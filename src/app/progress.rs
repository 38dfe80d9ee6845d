//! The course's progress, as plain data: what the student did with each level (not tried, tried,
//! solved, solved with help), how many attempts, each question's best answer, and the course's
//! order (topics in teaching order, the engine's stress levels last and not exercises). No file,
//! no Bevy: `progress_file.rs` keeps it between runs, `panels/course.rs` draws it.
//!
//! The rules (docs/student.md#the-course says the same to the student):
//! - a level is keyed by its path under the levels folder *and* its title ([`LevelKey`]): a
//!   different level put under an old file name does not inherit the old one's progress, and a
//!   record that no longer matches a level stays in the file, unshown, never deleted;
//! - an *attempt* is one run of the exercise in which at least one answer was graded (the grades
//!   clear when the run starts over: reset, a step back, the level opened again);
//! - each question keeps its best answer over every attempt ([`QuestionBest`]); a level is
//!   *solved* once every question has been answered right, in one attempt or over several, and
//!   *solved with help* when one of those right answers came after the worked solution was shown
//!   (`Exercise::help_used`) and was never answered right without it;
//! - the status never goes down: a later answer, wrong or with help, leaves a better one as it
//!   was, and a right answer without help later lifts "solved with help" to "solved";
//! - the *best error* is the worst question's best relative error: the largest, over the
//!   questions, of each question's smallest error (shown once every question was answered right).

use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// Where a level stands, worst to best (the order is the one a status never goes down in).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    NotTried,
    /// At least one answer was graded.
    Tried,
    /// Every question answered right, one of them only after the worked solution was shown.
    SolvedWithHelp,
    /// Every question answered right without the worked solution.
    Solved,
}

impl Status {
    pub fn is_solved(self) -> bool {
        self >= Status::SolvedWithHelp
    }

    /// The word the course prints for it.
    pub fn word(self) -> &'static str {
        match self {
            Status::NotTried => "—",
            Status::Tried => "tried",
            Status::SolvedWithHelp => "✔ help",
            Status::Solved => "✔ solved",
        }
    }

    /// What it means, for the row's hover text.
    pub fn meaning(self) -> &'static str {
        match self {
            Status::NotTried => "not tried yet",
            Status::Tried => "tried: not every question answered right yet",
            Status::SolvedWithHelp => {
                "solved with help: a question was answered right only after the worked solution was shown"
            }
            Status::Solved => "solved: every question answered right",
        }
    }
}

/// A level as progress knows it: its path under the levels folder (`kinetics/x.ron`, `/` between
/// folders) and its title.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct LevelKey {
    pub path: String,
    pub title: String,
}

/// A question's best answer so far.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuestionBest {
    /// Its relative error, |answer - expected| / |expected|.
    pub error: f64,
    /// It was right (within the question's student tolerance).
    pub right: bool,
    /// It was given after the worked solution was shown.
    pub help: bool,
}

impl QuestionBest {
    /// How good an answer is: right without help, then right with help, then wrong; then the
    /// smaller error.
    fn rank(&self) -> (u8, f64) {
        let class = match (self.right, self.help) {
            (true, false) => 0,
            (true, true) => 1,
            (false, _) => 2,
        };
        (class, self.error)
    }

    /// The better of two answers to one question.
    pub fn better(a: Option<QuestionBest>, b: Option<QuestionBest>) -> Option<QuestionBest> {
        match (a, b) {
            (Some(a), Some(b)) => {
                let (ra, rb) = (a.rank(), b.rank());
                let b_better = rb.0 < ra.0 || (rb.0 == ra.0 && rb.1.total_cmp(&ra.1).is_lt());
                Some(if b_better { b } else { a })
            }
            (a, None) => a,
            (None, b) => b,
        }
    }
}

/// What the student did with one level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Record {
    pub path: String,
    pub title: String,
    /// The best status reached (it never goes down).
    pub status: Status,
    /// Runs of the exercise in which at least one answer was graded.
    pub attempts: u32,
    /// Each question's best answer (None: never graded), as many as the level has questions.
    pub questions: Vec<Option<QuestionBest>>,
}

impl Record {
    fn new(key: &LevelKey, questions: usize) -> Record {
        Record {
            path: key.path.clone(),
            title: key.title.clone(),
            status: Status::NotTried,
            attempts: 0,
            questions: vec![None; questions],
        }
    }

    pub fn key(&self) -> LevelKey {
        LevelKey {
            path: self.path.clone(),
            title: self.title.clone(),
        }
    }

    /// How many questions have been answered right, of how many.
    pub fn right(&self) -> (usize, usize) {
        let right = self.questions.iter().flatten().filter(|q| q.right).count();
        (right, self.questions.len())
    }

    /// The worst question's best relative error, once every question was answered right.
    pub fn best_error(&self) -> Option<f64> {
        if self.questions.is_empty() || !self.questions.iter().all(|q| q.is_some_and(|q| q.right)) {
            return None;
        }
        self.questions
            .iter()
            .flatten()
            .map(|q| q.error)
            .max_by(f64::total_cmp)
    }

    /// The status the questions' best answers show on their own.
    fn status_of_questions(&self) -> Status {
        let graded = self.questions.iter().any(Option::is_some);
        let all_right =
            !self.questions.is_empty() && self.questions.iter().all(|q| q.is_some_and(|q| q.right));
        match (all_right, graded) {
            (true, _) if self.questions.iter().flatten().any(|q| q.help) => Status::SolvedWithHelp,
            (true, _) => Status::Solved,
            (false, true) => Status::Tried,
            (false, false) => Status::NotTried,
        }
    }

    /// Takes in a level whose number of questions is `n`: a record kept from a version of the
    /// level with another number of questions keeps its status and attempts, its answers start over.
    fn fit(&mut self, n: usize) {
        if self.questions.len() != n {
            self.questions = vec![None; n];
        }
    }
}

/// One graded answer, as the exercise panel holds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Graded {
    pub error: f64,
    pub right: bool,
}

/// Every level's record, and the first-steps tour's.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Progress {
    pub records: Vec<Record>,
    pub tour: TourRecord,
}

/// How far the student got in the first-steps tour (`panels/tour.rs`): the steps ticked, by
/// their ids (`tour::STEP_IDS`), and whether it was finished or hidden for good. Kept with the
/// course's progress, so that a reload of the page or a new window does not start it again.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TourRecord {
    pub ticked: Vec<String>,
    pub done: bool,
}

impl TourRecord {
    /// Nothing done yet (left out of the stored text).
    pub fn is_empty(&self) -> bool {
        self.ticked.is_empty() && !self.done
    }

    /// Takes in `other`'s (another window's): a step ticked in either stays ticked. True when
    /// that added anything.
    pub fn merge(&mut self, other: &TourRecord) -> bool {
        let before = (self.ticked.len(), self.done);
        for id in &other.ticked {
            if !self.ticked.contains(id) {
                self.ticked.push(id.clone());
            }
        }
        self.done |= other.done;
        before != (self.ticked.len(), self.done)
    }
}

impl Progress {
    pub fn get(&self, key: &LevelKey) -> Option<&Record> {
        self.records
            .iter()
            .find(|r| r.path == key.path && r.title == key.title)
    }

    pub fn status(&self, key: &LevelKey) -> Status {
        self.get(key).map_or(Status::NotTried, |r| r.status)
    }

    fn entry(&mut self, key: &LevelKey, questions: usize) -> &mut Record {
        let i = match self
            .records
            .iter()
            .position(|r| r.path == key.path && r.title == key.title)
        {
            Some(i) => i,
            None => {
                self.records.push(Record::new(key, questions));
                self.records.len() - 1
            }
        };
        let r = &mut self.records[i];
        r.fit(questions);
        r
    }

    /// A new attempt at a level of `questions` questions: its first answer was graded.
    pub fn begin_attempt(&mut self, key: &LevelKey, questions: usize) {
        let r = self.entry(key, questions);
        r.attempts = r.attempts.saturating_add(1);
        r.status = r.status.max(Status::Tried);
    }

    /// Question `k` (of `questions`) graded, `help` if the worked solution had been shown. Its
    /// best answer and the level's status are kept where they were better. Whether anything changed.
    pub fn grade(
        &mut self,
        key: &LevelKey,
        questions: usize,
        k: usize,
        g: Graded,
        help: bool,
    ) -> bool {
        let r = self.entry(key, questions);
        let before = r.clone();
        if let Some(slot) = r.questions.get_mut(k) {
            let answer = QuestionBest {
                error: if g.error.is_nan() {
                    f64::INFINITY
                } else {
                    g.error
                },
                right: g.right,
                help: help && g.right,
            };
            *slot = QuestionBest::better(*slot, Some(answer));
        }
        r.status = r.status.max(r.status_of_questions());
        *r != before
    }

    /// Takes in records written elsewhere (another window, since this one read the file): each
    /// level keeps the better of the two (status, attempts, each question's best answer), and a
    /// level only they know is added.
    pub fn merge(&mut self, other: &Progress) {
        self.tour.merge(&other.tour);
        for o in &other.records {
            match self
                .records
                .iter_mut()
                .find(|r| r.path == o.path && r.title == o.title)
            {
                None => self.records.push(o.clone()),
                Some(r) => {
                    r.status = r.status.max(o.status);
                    r.attempts = r.attempts.max(o.attempts);
                    if r.questions.len() == o.questions.len() {
                        for (a, b) in r.questions.iter_mut().zip(&o.questions) {
                            *a = QuestionBest::better(*a, *b);
                        }
                    }
                }
            }
        }
    }
}

/// Stars for a challenge met at its `launches`-th launch: 3 in one or two, 2 in three or four,
/// 1 after (the Challenge box and the course give the same).
pub fn stars(launches: u32) -> u8 {
    match launches {
        0..=2 => 3,
        3..=4 => 2,
        _ => 1,
    }
}

/// A challenge as the course records it: one goal, a launch an attempt while it is not met
/// (a launch after it is met is play, not an attempt: the stars stay those it was met with).
/// Whether anything changed.
pub fn launch(progress: &mut Progress, key: &LevelKey, met: bool, error: f64) -> bool {
    if progress.status(key).is_solved() {
        return false;
    }
    progress.begin_attempt(key, 1);
    progress.grade(key, 1, 0, Graded { error, right: met }, false);
    true
}

/// A challenge's stars as recorded: those of the launch that met it, None while it is not met.
pub fn challenge_stars(progress: &Progress, key: &LevelKey) -> Option<u8> {
    progress
        .get(key)
        .filter(|r| r.status.is_solved())
        .map(|r| stars(r.attempts))
}

/// The course's topics in teaching order (the levels folder's sub-folders).
pub const TEACHING_ORDER: [&str; 6] = [
    "kinematics",
    "kinetics",
    "energy",
    "momentum",
    "impact",
    "virtual-work",
];

/// The folder of the engine's stress levels: listed last, not exercises.
pub const STRESS_TOPIC: &str = "stress";

/// What kind of topic a folder is, in the order the course lists them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum TopicKind {
    /// One of [`TEACHING_ORDER`], by its place there.
    Taught(usize),
    /// Another folder of exercises (a teacher's own), after the taught ones.
    Other,
    /// The levels the user saved from the window.
    Saved,
    /// The engine's stress levels: not exercises.
    Stress,
}

impl TopicKind {
    /// A topic's kind by its folder name (`kinetics`, `kinetics/extra`, `saved (...)`, `stress`).
    pub fn of(topic: &str) -> TopicKind {
        let top = topic.split('/').next().unwrap_or(topic);
        if let Some(i) = TEACHING_ORDER.iter().position(|t| *t == top) {
            TopicKind::Taught(i)
        } else if top == STRESS_TOPIC {
            TopicKind::Stress
        } else if topic.starts_with("saved") {
            TopicKind::Saved
        } else {
            TopicKind::Other
        }
    }

    /// Its levels count in the course (solved/total, the next level).
    pub fn is_course(self) -> bool {
        matches!(self, TopicKind::Taught(_) | TopicKind::Other)
    }
}

/// Orders topics as the course lists them: teaching order, other folders, saved levels, stress;
/// by name within a kind.
pub fn topic_order(a: &str, b: &str) -> Ordering {
    (TopicKind::of(a), a).cmp(&(TopicKind::of(b), b))
}

/// The next level to open after `current` (an index into `course`, the course's exercises in
/// order): the first one after it that is not solved, going round to the start; from outside the
/// course (`None`), the first not solved. None when every exercise is solved.
pub fn next_unsolved(
    course: &[LevelKey],
    current: Option<usize>,
    progress: &Progress,
) -> Option<usize> {
    let n = course.len();
    let start = current.map_or(0, |c| c + 1);
    (0..n)
        .map(|i| (start + i) % n)
        .filter(|&i| Some(i) != current)
        .find(|&i| !progress.status(&course[i]).is_solved())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(path: &str) -> LevelKey {
        LevelKey {
            path: path.into(),
            title: format!("title of {path}"),
        }
    }

    const RIGHT: Graded = Graded {
        error: 0.004,
        right: true,
    };
    const WRONG: Graded = Graded {
        error: 0.3,
        right: false,
    };

    #[test]
    fn a_graded_answer_makes_a_level_tried_and_all_right_solved() {
        let (mut p, k) = (Progress::default(), key("kinetics/a.ron"));
        assert_eq!(p.status(&k), Status::NotTried);
        p.begin_attempt(&k, 2);
        p.grade(&k, 2, 0, WRONG, false);
        assert_eq!(p.status(&k), Status::Tried);
        p.grade(&k, 2, 0, RIGHT, false);
        assert_eq!(p.status(&k), Status::Tried, "one question of two is right");
        p.grade(
            &k,
            2,
            1,
            Graded {
                error: 0.001,
                right: true,
            },
            false,
        );
        assert_eq!(p.status(&k), Status::Solved);
        let r = p.get(&k).unwrap();
        assert_eq!((r.attempts, r.right()), (1, (2, 2)));
        // The worst question's best error: question 0's 0.004 over question 1's 0.001.
        assert_eq!(r.best_error(), Some(0.004));
    }

    #[test]
    fn questions_answered_right_in_different_attempts_solve_the_level() {
        let (mut p, k) = (Progress::default(), key("energy/b.ron"));
        p.begin_attempt(&k, 2);
        p.grade(&k, 2, 0, RIGHT, false);
        p.begin_attempt(&k, 2);
        p.grade(&k, 2, 1, RIGHT, false);
        assert_eq!(p.status(&k), Status::Solved);
        assert_eq!(p.get(&k).unwrap().attempts, 2);
    }

    #[test]
    fn help_makes_it_solved_with_help_and_nothing_goes_down() {
        let (mut p, k) = (Progress::default(), key("impact/c.ron"));
        p.begin_attempt(&k, 1);
        p.grade(&k, 1, 0, RIGHT, true);
        assert_eq!(p.status(&k), Status::SolvedWithHelp);
        // A wrong answer later does not undo the solve.
        p.begin_attempt(&k, 1);
        p.grade(&k, 1, 0, WRONG, false);
        assert_eq!(p.status(&k), Status::SolvedWithHelp);
        // Right without help: solved.
        p.grade(&k, 1, 0, RIGHT, false);
        assert_eq!(p.status(&k), Status::Solved);
        // Then right again with help, and wrong: still solved, the clean answer kept.
        p.grade(
            &k,
            1,
            0,
            Graded {
                error: 0.0,
                right: true,
            },
            true,
        );
        p.grade(&k, 1, 0, WRONG, false);
        assert_eq!(p.status(&k), Status::Solved);
        assert!(!p.get(&k).unwrap().questions[0].unwrap().help);
    }

    #[test]
    fn a_wrong_answer_with_help_does_not_count_as_help() {
        let (mut p, k) = (Progress::default(), key("kinetics/d.ron"));
        p.begin_attempt(&k, 2);
        p.grade(&k, 2, 0, WRONG, true);
        p.grade(&k, 2, 0, RIGHT, false);
        p.grade(&k, 2, 1, RIGHT, false);
        assert_eq!(p.status(&k), Status::Solved);
    }

    #[test]
    fn another_title_under_the_same_path_starts_afresh() {
        let mut p = Progress::default();
        let old = key("kinetics/e.ron");
        p.begin_attempt(&old, 1);
        p.grade(&old, 1, 0, RIGHT, false);
        let new = LevelKey {
            title: "another level".into(),
            ..old.clone()
        };
        assert_eq!(p.status(&new), Status::NotTried);
        assert_eq!(p.status(&old), Status::Solved);
    }

    #[test]
    fn a_changed_number_of_questions_keeps_the_status_not_the_answers() {
        let (mut p, k) = (Progress::default(), key("kinetics/f.ron"));
        p.begin_attempt(&k, 1);
        p.grade(&k, 1, 0, RIGHT, false);
        p.begin_attempt(&k, 2);
        let r = p.get(&k).unwrap();
        assert_eq!(
            (r.status, r.right(), r.attempts),
            (Status::Solved, (0, 2), 2)
        );
    }

    #[test]
    fn merging_keeps_the_better_of_each() {
        let (a, b) = (key("kinetics/a.ron"), key("energy/b.ron"));
        let mut mine = Progress::default();
        mine.begin_attempt(&a, 1);
        mine.grade(&a, 1, 0, WRONG, false);
        let mut theirs = Progress::default();
        for _ in 0..3 {
            theirs.begin_attempt(&a, 1);
        }
        theirs.grade(&a, 1, 0, RIGHT, false);
        theirs.begin_attempt(&b, 1);
        mine.merge(&theirs);
        assert_eq!(mine.status(&a), Status::Solved);
        assert_eq!(mine.get(&a).unwrap().attempts, 3);
        assert_eq!(mine.status(&b), Status::Tried);
    }

    #[test]
    fn topics_come_in_teaching_order_with_stress_last() {
        let mut topics = vec![
            "stress",
            "saved (saved-levels/)",
            "virtual-work",
            "impact",
            "my-class",
            "kinetics",
            "momentum",
            "energy",
            "kinematics",
        ];
        topics.sort_by(|a, b| topic_order(a, b));
        assert_eq!(
            topics,
            [
                "kinematics",
                "kinetics",
                "energy",
                "momentum",
                "impact",
                "virtual-work",
                "my-class",
                "saved (saved-levels/)",
                "stress"
            ]
        );
        assert!(!TopicKind::of("stress").is_course());
        assert!(TopicKind::of("kinetics/extra").is_course());
    }

    #[test]
    fn the_next_level_is_the_next_unsolved_going_round() {
        let course: Vec<LevelKey> = ["a", "b", "c", "d"].iter().map(|p| key(p)).collect();
        let mut p = Progress::default();
        let solve = |p: &mut Progress, k: &LevelKey| {
            p.begin_attempt(k, 1);
            p.grade(k, 1, 0, RIGHT, false);
        };
        solve(&mut p, &course[1]);
        // From a: b is solved, c is next.
        assert_eq!(next_unsolved(&course, Some(0), &p), Some(2));
        // From d: round to a.
        assert_eq!(next_unsolved(&course, Some(3), &p), Some(0));
        // Tried but not solved counts as unsolved.
        p.begin_attempt(&course[2], 1);
        assert_eq!(next_unsolved(&course, Some(1), &p), Some(2));
        // From outside the course: the first unsolved.
        solve(&mut p, &course[0]);
        assert_eq!(next_unsolved(&course, None, &p), Some(2));
        // Every other one solved: none (the current one is not offered again).
        for k in &course[2..] {
            solve(&mut p, k);
        }
        assert_eq!(next_unsolved(&course, Some(0), &p), None);
    }
}
