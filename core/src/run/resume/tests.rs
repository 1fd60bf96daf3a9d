use super::*;
use crate::export::Source;
use crate::sim::sessions::adaptive;

fn chosen(session: &Session) -> Calibration {
    Source::from_session(session, "s.json").unwrap().calibration
}

#[test]
fn a_resumed_run_without_turns_keeps_an_earlier_upload_s_g_or_says_why_it_has_none() {
    let session = adaptive(1, 0.0, 0.004);
    let chosen = chosen(&session);
    let why = || "only 0 usable turns".to_owned();
    let (none, outcome, said) = gyro_without_fit(why(), true, &session, &chosen, GyroOutcome::default());
    assert_eq!(none.gyro.matrix, chosen.gyro.matrix);
    assert!(outcome.not_fitted.is_some_and(|w| w.contains("a resumed session has only the turns")), "{said}");
    let mut uploaded = chosen;
    uploaded.gyro.matrix = [[1.02, 0.0, 0.0], [0.0, 0.98, 0.0], [0.0, 0.0, 1.01]];
    let session = Session { uploaded: Some(uploaded), ..session };
    let (kept, outcome, said) = gyro_without_fit(why(), true, &session, &chosen, GyroOutcome::default());
    assert_eq!(kept.gyro.matrix, uploaded.gyro.matrix);
    assert_eq!(kept.offset_g, chosen.offset_g, "only G is the earlier upload's");
    assert!(outcome.not_fitted.is_none() && said.contains("G kept"), "{said}");
    // A first run has no earlier upload to keep: it says why there is no G.
    let (first, outcome, said) = gyro_without_fit(why(), false, &session, &chosen, GyroOutcome::default());
    assert_eq!(first.gyro.matrix, chosen.gyro.matrix);
    assert_eq!(outcome.not_fitted.as_deref(), Some("only 0 usable turns"), "{said}");
}

#[test]
fn a_resumed_run_claims_no_board_time_and_a_first_run_claims_its_first_capture_s() {
    assert_eq!(board_time_start(Some(12.5), false), Some(12.5));
    assert_eq!(board_time_start(Some(12.5), true), None);
    assert_eq!(board_time_start(None, false), None);
}

#[test]
fn the_session_kept_before_verifying_holds_the_upload_and_every_capture() {
    let session = adaptive(2, 0.5, 0.004);
    let uploaded = chosen(&session);
    assert_eq!(session.uploaded, None);
    let kept = kept_before_verifying(&session, uploaded);
    assert_eq!(kept.uploaded, Some(uploaded));
    assert_eq!((kept.captures.len(), &kept.captures), (15, &session.captures));
}

#[test]
fn a_resumed_session_goes_on_as_begun_and_says_which_arguments_it_does_not_use() {
    assert!(resumed_as_begun(SessionKind::Adaptive, false, None).is_empty());
    assert!(resumed_as_begun(SessionKind::Quick, true, Some(4)).is_empty(), "a quick session's --seconds");
    let quick = resumed_as_begun(SessionKind::Quick, false, None);
    assert_eq!(quick.len(), 1);
    assert!(
        quick[0].contains("begun as a calibration fitted on the chip") && quick[0].contains("leaving out --chip-fit"),
        "{quick:?}"
    );
    let full = resumed_as_begun(SessionKind::Adaptive, true, Some(6));
    assert_eq!(full.len(), 2, "{full:?}");
    assert!(full[0].contains("begun as a full calibration") && full[0].contains("(--chip-fit is not used"), "{full:?}");
    assert!(full[1].contains("--seconds 6 is not used"), "{full:?}");
}

#[test]
fn a_new_session_is_quick_fixed_or_adaptive_as_asked() {
    assert_eq!(SessionKind::asked(true, Some(4)), SessionKind::Quick);
    assert_eq!(SessionKind::asked(false, Some(4)), SessionKind::Fixed);
    assert_eq!(SessionKind::asked(false, None), SessionKind::Adaptive);
}
