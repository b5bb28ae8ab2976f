"""Resume-link codes (server/admin/resume.py): valid for the participant's current token until the expiry;
void after the token changes (a used link), after the expiry, under another secret, or when altered."""

from __future__ import annotations

from server.admin.resume import link_secret, make_code, read_code, resume_path, verify

SECRET = link_secret("admin-secret")


def test_a_code_verifies_only_for_the_token_it_was_made_for_and_until_it_expires():
    code = make_code(SECRET, "abc123", "hash-1", expires=1_000)
    parsed = read_code(code)
    assert parsed is not None and (parsed.public_id, parsed.expires) == ("abc123", 1_000)
    assert verify(SECRET, parsed, "hash-1", now=1_000)
    assert not verify(SECRET, parsed, "hash-1", now=1_001), "expired"
    assert not verify(SECRET, parsed, "hash-2", now=10), "the token changed: the link was used"
    assert not verify(link_secret("another-admin-token"), parsed, "hash-1", now=10), "another deployment's link"
    forged = read_code(code.replace(".1000.", ".9999."))
    assert forged is not None and not verify(SECRET, forged, "hash-1", now=10), "a later expiry is not signed"


def test_malformed_codes_are_not_read_and_the_code_rides_in_the_fragment():
    for bad in ("", "a.b", "a.1.", ".1.sig", "a.x.sig", "a.1.sig.extra", "a." + "9" * 13 + ".sig"):
        assert read_code(bad) is None, bad
    assert resume_path("paper_study", "abc.1.sig") == "/?study=paper_study#resume=abc.1.sig"
