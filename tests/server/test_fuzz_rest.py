"""Property-based fuzzing of the REST API from its own OpenAPI schema (``GET /openapi.json``).

Requests are generated for every operation the schema lists (participant, admin, health, exports): path
and query parameters and JSON bodies drawn from the operation's JSON schemas, then often broken — wrong
types, unknown fields, arbitrary JSON, bytes that are not JSON, odd content types, hostile path segments —
and sent with no token, a garbage token, participants' tokens in every state of the flow, or the admin
token. The property: the server never answers 5xx, and every error it answers is JSON with a ``detail``.
Texts include lone UTF-16 surrogates and NUL (in keys, values, path segments and query strings): a body
holding one answers 422 ``string_unstorable``, and the run checks that some did.
Numbers include ``NaN`` and ``±Infinity`` (as Python's and JavaScript's JSON writers may send them) and
integers far beyond 64 bits; some bodies pass the body limit. A second test sends the known hostile inputs
one by one: non-finite and out-of-range numbers (422 naming the field), bodies over the limit, declared or
streamed (413, never read or echoed), out-of-range path ids (404 / 422), and long inputs (quoted at most as a
short excerpt).
"""

from __future__ import annotations

import asyncio
import math
from typing import Any
from urllib.parse import quote, urlencode

import httpx
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from steakhouse_testing import Player, play_to_end

pytestmark = pytest.mark.store_agnostic

REQUESTS_PER_EXAMPLE = 6
EXAMPLES = 150
LIMIT = 64 * 1024

UNSTORABLE = ["\ud800", "\udbff", "\udc00", "\udfff", "\x00"]
"""Lone UTF-16 surrogates (JSON can spell them, UTF-8 cannot) and NUL (PostgreSQL's text refuses it)."""


def texts(max_size: int) -> st.SearchStrategy[str]:
    """Any text, sometimes with lone surrogates or NUL mixed in."""
    return st.one_of(st.text(max_size=max_size), st.lists(st.one_of(st.sampled_from(UNSTORABLE), st.characters()),
                                                          min_size=1, max_size=max_size).map("".join))


json_leaf = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.integers(-10**40, 10**40),
                      st.floats(), texts(20))
json_value = st.recursive(json_leaf, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(texts(10), inner, max_size=4)), max_leaves=12)
hostile_text = st.one_of(st.text(max_size=80), st.sampled_from(
    ["", ".", "..", "../..", "%00", "\x00", "1 OR 1=1", "' OR '1'='1", "<script>", "a" * 5000, "-1", "0",
     str(2**63), str(-(2**63) - 1), "1e9", "NaN", "null", "true", "tiny", "paper_study", "ü", "😀", "/", "?"]))


def from_schema(schema: dict[str, Any], components: dict[str, Any], depth: int = 0) -> st.SearchStrategy[Any]:
    """A strategy for values valid under (the subset of JSON Schema FastAPI emits for) ``schema``."""
    if "$ref" in schema:
        return from_schema(components[schema["$ref"].rsplit("/", 1)[1]], components, depth)
    if depth > 4:
        return json_leaf
    for key in ("anyOf", "oneOf"):
        if key in schema:
            return st.one_of(*(from_schema(s, components, depth + 1) for s in schema[key]))
    if "allOf" in schema:
        return from_schema(schema["allOf"][0], components, depth + 1)
    if "enum" in schema:
        return st.sampled_from(schema["enum"])
    if "const" in schema:
        return st.just(schema["const"])
    kind = schema.get("type")
    if kind == "string":
        return texts(min(schema.get("maxLength", 40), 300))
    if kind == "integer":
        return st.integers(schema.get("minimum", -(2**63)), schema.get("maximum", 2**63))
    if kind == "number":
        return st.floats()
    if kind == "boolean":
        return st.booleans()
    if kind == "null":
        return st.none()
    if kind == "array":
        return st.lists(from_schema(schema.get("items", {}), components, depth + 1), max_size=4)
    if kind == "object" or "properties" in schema:
        properties = schema.get("properties", {})
        required = set(schema.get("required", ()))
        fixed = st.fixed_dictionaries(
            {k: from_schema(v, components, depth + 1) for k, v in properties.items() if k in required},
            optional={k: from_schema(v, components, depth + 1) for k, v in properties.items() if k not in required})
        extra = schema.get("additionalProperties", True)
        if extra is False:
            return fixed
        values = json_value if extra is True else from_schema(extra, components, depth + 1)
        more = st.dictionaries(texts(min(schema.get("propertyNames", {}).get("maxLength", 20), 20)),
                               values, max_size=min(schema.get("maxProperties", 4), 4))
        return st.tuples(fixed, more).map(lambda pair: {**pair[1], **pair[0]})
    return json_value


def operations(spec: dict[str, Any]) -> list[tuple[str, str, dict[str, Any]]]:
    return [(method.upper(), path, op) for path, ops in spec["paths"].items() for method, op in ops.items()]


@st.composite
def requests(draw: st.DrawFn, ops: list[tuple[str, str, dict[str, Any]]], components: dict[str, Any],
             tokens: list[str]) -> dict[str, Any]:
    method, path, op = draw(st.sampled_from(ops))
    params: dict[str, Any] = {}
    for parameter in op.get("parameters", []):
        broken = draw(st.integers(0, 4)) == 0
        value = draw(hostile_text if broken else from_schema(parameter.get("schema", {}), components))
        if parameter["in"] == "path":
            text = value if isinstance(value, str) else str(value).lower() if isinstance(value, bool) else str(value)
            path = path.replace("{" + parameter["name"] + "}", quote(text, safe="", errors="surrogatepass") or "x")
        elif parameter["in"] == "query" and value is not None and draw(st.integers(0, 4)) > 0:
            params[parameter["name"]] = value if isinstance(value, str) else str(value)
    if draw(st.integers(0, 5)) == 0:
        params[draw(st.text(min_size=1, max_size=10))] = draw(st.text(max_size=20))
    headers = {}
    token = draw(st.sampled_from([None, "garbage", *tokens]))
    if token is not None:
        headers["Authorization"] = draw(st.sampled_from(["Bearer ", "bearer ", "Basic ", ""])) + token
    content: bytes | None = None
    body_schema = (op.get("requestBody", {}).get("content", {}).get("application/json", {}).get("schema"))
    shape = draw(st.sampled_from(["schema", "schema", "json", "bytes", "none", "big"]))
    if shape == "schema" and body_schema is not None:
        content = _dumps(draw(from_schema(body_schema, components)))
    elif shape == "json" or (shape == "schema" and body_schema is None):
        content = _dumps(draw(json_value))
    elif shape == "bytes":
        content = draw(st.binary(max_size=300))
    elif shape == "big":
        content = b'{"recruiting": {"PROLIFIC_PID": "' + b"a" * LIMIT + b'"}}'
    if content is not None:
        headers["Content-Type"] = draw(st.sampled_from(["application/json", "application/json", "text/plain",
                                                        "application/x-www-form-urlencoded", "application/xml"]))
    query = urlencode(params, errors="surrogatepass")  # a lone surrogate goes as its (invalid UTF-8) bytes
    return {"method": method, "url": path + ("?" + query if query else ""), "headers": headers, "content": content}


def _dumps(value: Any) -> bytes:
    import json

    return json.dumps(value, allow_nan=True).encode()


async def participants_in_every_state(url: str) -> list[str]:
    """Tokens of participants at consent, instructions, a trial, a questionnaire, and screened out."""
    tokens = []
    for steps in (0, 1, 2):
        player = Player(url)
        await player.join(PROLIFIC_PID=f"fuzz-{steps}")
        if steps >= 1:
            await player.post("/api/session/consent", {"accept": True})
        if steps >= 2:
            await player.post("/api/session/instructions_done")
        tokens.append(player.token)
        await player.close()
    player = Player(url)
    await player.ready(PROLIFIC_PID="fuzz-played")
    sock = await player.socket()
    await play_to_end(sock)
    await sock.close()
    tokens.append(player.token)
    await player.close()
    player = Player(url)
    await player.join(PROLIFIC_PID="fuzz-declined")
    await player.post("/api/session/consent", {"accept": False})
    tokens.append(player.token)
    await player.close()
    return tokens


def test_no_generated_request_gets_a_5xx(live_server, study_file):
    study = study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1})
    server = live_server([study], join_rate_per_minute=0)
    tokens = [*asyncio.run(participants_in_every_state(server.url)), "admin-secret"]
    with httpx.Client(base_url=server.url, timeout=60) as client:
        spec = client.get("/openapi.json").json()
        ops = operations(spec)
        assert len(ops) >= 15, [f"{m} {p}" for m, p, _ in ops]
        components = spec.get("components", {}).get("schemas", {})
        seen: dict[int | str, int] = {}

        @settings(max_examples=EXAMPLES, deadline=None, database=None, phases=(Phase.explicit, Phase.generate),
                  suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                                         HealthCheck.data_too_large])
        @given(batch=st.lists(requests(ops, components, tokens), min_size=REQUESTS_PER_EXAMPLE,
                              max_size=REQUESTS_PER_EXAMPLE))
        def fuzz(batch: list[dict[str, Any]]) -> None:
            for request in batch:
                response = client.request(**request)
                seen[response.status_code] = seen.get(response.status_code, 0) + 1
                if response.status_code == 422 and "string_unstorable" in response.text:
                    seen["unstorable"] = seen.get("unstorable", 0) + 1
                where = f"{request['method']} {request['url']} → {response.status_code}"
                assert response.status_code < 500, f"{where}: {response.text[:300]}"
                assert len(response.content) < 16_384 or response.status_code < 300, f"{where}: a long error"
                if response.status_code >= 400 and response.headers.get("content-type", "").startswith(
                        "application/json"):
                    assert "detail" in response.json(), where
                assert "Traceback" not in response.text, where

        fuzz()
    assert sum(v for k, v in seen.items() if isinstance(k, int)) >= EXAMPLES * REQUESTS_PER_EXAMPLE
    assert math.fsum(v for k, v in seen.items() if isinstance(k, int) and k < 300) > 0, seen
    assert {401, 422} <= set(seen), seen
    assert seen.get("unstorable", 0) > 0, "some bodies carried lone surrogates or NUL, and got a 422 naming them"


def _raw(client: httpx.Client, method: str, path: str, body: str | bytes, token: str | None = None,
         **headers: str) -> httpx.Response:
    sent = {"Content-Type": "application/json", **headers}
    if token:
        sent["Authorization"] = f"Bearer {token}"
    return client.request(method, path, content=body.encode() if isinstance(body, str) else body, headers=sent)


def _fields(response: httpx.Response) -> list[str]:
    """The last part of each problem's location (the field the 422 names)."""
    return [str(problem["loc"][-1]) for problem in response.json()["detail"]]


def test_hostile_inputs_get_a_4xx_naming_the_field_and_no_echo(live_server, study_file):
    study = study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1},
                       quiz={"questions": [{"id": "seen", "text": "?", "options": ["a", "b"], "answer": 1,
                                            "explanation": "a"}]})
    server = live_server([study])
    with httpx.Client(base_url=server.url, timeout=60) as client:
        for number in ("NaN", "Infinity", "-Infinity", "1e400"):
            response = _raw(client, "POST", "/api/studies/tiny/join", f'{{"recruiting": {{"PROLIFIC_PID": {number}}}}}')
            assert response.status_code == 422 and _fields(response) == ["PROLIFIC_PID"], response.text
            response = _raw(client, "POST", "/api/studies/tiny/join", f'{{"test_run": {number}}}')
            assert response.status_code == 422 and _fields(response) == ["test_run"], response.text
        token = client.post("/api/studies/tiny/join", json={}).json()["token"]
        device = ('{"screen_width": 1920, "screen_height": 1080, "viewport_width": 1600, "viewport_height": 900, '
                  '"pixel_ratio": %s, "fine_pointer": true, "touch": false}')
        for number in ("NaN", "Infinity", "1e400", "-1", "1e9"):
            response = _raw(client, "POST", "/api/session/device", device % number, token)
            assert response.status_code == 422 and _fields(response) == ["pixel_ratio"], response.text
        response = _raw(client, "POST", "/api/session/device", device.replace("1920", "1" + "0" * 30) % "1", token)
        assert response.status_code == 422 and _fields(response) == ["screen_width"], response.text
        _raw(client, "POST", "/api/session/consent", '{"accept": true}', token)
        _raw(client, "POST", "/api/session/instructions_done", "", token)
        for number in ("NaN", "Infinity", "1e400", str(10**30), "-" + "9" * 4000):
            response = _raw(client, "POST", "/api/session/quiz", f'{{"answers": {{"seen": {number}}}}}', token)
            assert response.status_code == 422 and _fields(response) == ["seen"], response.text
            assert len(response.content) < 1000, "the number is quoted as a short excerpt at most"
        huge_int = _raw(client, "POST", "/api/session/quiz", '{"answers": {"seen": ' + "9" * 5000 + "}}", token)
        assert 400 <= huge_int.status_code < 500 and "9" * 100 not in huge_int.text
        # Bodies over the limit: 413 from the declared length, before anything is read; streamed: at the limit.
        big = b'{"recruiting": {"PROLIFIC_PID": "' + b"x" * (10 << 20) + b'"}}'
        for sent in (big, iter([big[i:i + 65536] for i in range(0, len(big), 65536)])):
            response = client.post("/api/studies/tiny/join", content=sent, headers={"Content-Type": "application/json"})
            assert response.status_code == 413 and response.json()["detail"]["code"] == "too_large"
            assert len(response.content) < 200
        # Just under the limit: the 422 quotes a short excerpt, never the input.
        long = _raw(client, "POST", "/api/studies/tiny/join", '{"recruiting": {"PROLIFIC_PID": "' + "y" * 60000 + '"}}')
        assert long.status_code == 422 and "y" * 100 not in long.text and len(long.content) < 1000
        unknown = _raw(client, "POST", "/api/studies/tiny/join", '{"' + "k" * 60000 + '": 1}')
        assert unknown.status_code == 422 and "k" * 100 not in unknown.text
        # Out-of-range path ids: 404 or 422 naming the id, never 5xx.
        admin = {"Authorization": "Bearer admin-secret"}
        for trial_id in ("1" + "0" * 22, str(2**63), "-1", "0", "1e3", "NaN"):
            for path in ("/api/admin/trials/{}", "/api/admin/trials/{}/frames", "/api/admin/trials/{}/events",
                         "/api/admin/live/{}"):
                response = client.get(path.format(trial_id), headers=admin)
                assert response.status_code == 422 and _fields(response) == ["trial_id"], (path, response.text)
        assert client.get("/api/admin/trials/" + str(2**63 - 1), headers=admin).status_code == 404
        huge_start = client.get("/api/admin/trials/1/frames", params={"start": "9" * 30}, headers=admin)
        assert huge_start.status_code == 422 and _fields(huge_start) == ["start"]
        for path in ("/api/admin/participants/{}/answers", "/api/admin/participants/{}/resume_link"):
            method = "POST" if path.endswith("link") else "GET"
            response = client.request(method, path.format("p" * 5000), headers=admin)
            assert response.status_code == 422 and "p" * 100 not in response.text
