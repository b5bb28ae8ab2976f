"""Property-based fuzzing of the REST API from its own OpenAPI schema (``GET /openapi.json``).

Requests are generated for every operation the schema lists (participant, admin, health, exports): path
and query parameters and JSON bodies drawn from the operation's JSON schemas, then often broken — wrong
types, unknown fields, arbitrary JSON, bytes that are not JSON, odd content types, hostile path segments —
and sent with no token, a garbage token, participants' tokens in every state of the flow, or the admin
token. The property: the server never answers 5xx, and every error it answers is JSON with a ``detail``.
"""

from __future__ import annotations

import asyncio
import math
from typing import Any
from urllib.parse import quote

import httpx
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from steakhouse_testing import Player, play_to_end

REQUESTS_PER_EXAMPLE = 6
EXAMPLES = 150

json_leaf = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70),
                      st.floats(allow_nan=False, allow_infinity=False), st.text(max_size=20))
json_value = st.recursive(json_leaf, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=10), inner, max_size=4)), max_leaves=12)
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
        return st.text(max_size=min(schema.get("maxLength", 40), 300))
    if kind == "integer":
        return st.integers(schema.get("minimum", -(2**63)), schema.get("maximum", 2**63))
    if kind == "number":
        return st.floats(allow_nan=False, allow_infinity=False)
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
        more = st.dictionaries(st.text(max_size=min(schema.get("propertyNames", {}).get("maxLength", 20), 20)),
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
            path = path.replace("{" + parameter["name"] + "}", quote(text, safe="") or "x")
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
    shape = draw(st.sampled_from(["schema", "schema", "json", "bytes", "none"]))
    if shape == "schema" and body_schema is not None:
        content = _dumps(draw(from_schema(body_schema, components)))
    elif shape == "json" or (shape == "schema" and body_schema is None):
        content = _dumps(draw(json_value))
    elif shape == "bytes":
        content = draw(st.binary(max_size=300))
    if content is not None:
        headers["Content-Type"] = draw(st.sampled_from(["application/json", "application/json", "text/plain",
                                                        "application/x-www-form-urlencoded", "application/xml"]))
    return {"method": method, "url": path, "params": params, "headers": headers, "content": content}


def _dumps(value: Any) -> bytes:
    import json

    return json.dumps(value, allow_nan=False).encode()


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


@pytest.mark.parametrize("db_url", ["sqlite"], indirect=True)
def test_no_generated_request_gets_a_5xx(live_server, study_file):
    study = study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1})
    server = live_server([study], join_rate_per_minute=0)
    tokens = [*asyncio.run(participants_in_every_state(server.url)), "admin-secret"]
    with httpx.Client(base_url=server.url, timeout=60) as client:
        spec = client.get("/openapi.json").json()
        ops = operations(spec)
        assert len(ops) >= 15, [f"{m} {p}" for m, p, _ in ops]
        components = spec.get("components", {}).get("schemas", {})
        seen: dict[int, int] = {}

        @settings(max_examples=EXAMPLES, deadline=None, database=None, phases=(Phase.explicit, Phase.generate),
                  suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                                         HealthCheck.data_too_large])
        @given(batch=st.lists(requests(ops, components, tokens), min_size=REQUESTS_PER_EXAMPLE,
                              max_size=REQUESTS_PER_EXAMPLE))
        def fuzz(batch: list[dict[str, Any]]) -> None:
            for request in batch:
                response = client.request(**request)
                seen[response.status_code] = seen.get(response.status_code, 0) + 1
                where = f"{request['method']} {request['url']} {request['params']} → {response.status_code}"
                assert response.status_code < 500, f"{where}: {response.text[:300]}"
                if response.status_code >= 400 and response.headers.get("content-type", "").startswith(
                        "application/json"):
                    assert "detail" in response.json(), where
                assert "Traceback" not in response.text, where

        fuzz()
    assert sum(seen.values()) >= EXAMPLES * REQUESTS_PER_EXAMPLE
    assert math.fsum(v for k, v in seen.items() if k < 300) > 0, seen
    assert {401, 422} <= set(seen), seen
