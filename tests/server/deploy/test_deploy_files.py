"""The deployment files agree with each other and with the docs (Docker cannot run where the suite runs, so
these checks keep ``server/deploy/compose.yaml`` and the ``Dockerfile`` honest; nginx itself runs in
``test_nginx_deploy.py``):

- nginx's upstreams name exactly the compose file's app services, on the port the ``Dockerfile`` exposes and
  serves; the compose file mounts ``nginx.conf`` and the ``tls`` folder where the configuration reads them;
- the apps get a PostgreSQL URL on the ``db`` service, the admin token and study files from ``.env``;
- ``docs/operations.md`` refers to the configuration file instead of carrying a copy of it.
"""

from __future__ import annotations

import re
from typing import Any

import pytest
import yaml
from nginx_proxy import CONFIG, render
from steakhouse_testing import REPO

DEPLOY = REPO / "server" / "deploy"


def compose() -> dict[str, Any]:
    parsed: dict[str, Any] = yaml.safe_load((DEPLOY / "compose.yaml").read_text(encoding="utf-8"))
    return parsed


def test_the_proxy_the_compose_file_and_the_image_agree():
    nginx = CONFIG.read_text(encoding="utf-8")
    services = compose()["services"]
    dockerfile = (REPO / "Dockerfile").read_text(encoding="utf-8")
    port = re.search(r"^EXPOSE (\d+)$", dockerfile, re.MULTILINE)
    assert port is not None and f'"--port", "{port.group(1)}"' in dockerfile
    upstreams = re.findall(r"^\s*server (\S+):(\d+)", nginx, re.MULTILINE)
    apps = sorted(name for name, spec in services.items() if "build" in spec)
    assert apps == ["app1", "app2"] and set(services) == {"db", "app1", "app2", "nginx"}
    assert sorted(set(upstreams)) == [(app, port.group(1)) for app in apps], "each upstream lists every app"
    assert services["app1"] == services["app2"]
    mounts = services["nginx"]["volumes"]
    assert "./nginx.conf:/etc/nginx/nginx.conf:ro" in mounts and "./tls:/etc/nginx/tls:ro" in mounts
    assert "/etc/nginx/tls/study.crt" in nginx and "/etc/nginx/tls/study.key" in nginx
    env = services["app1"]["environment"]
    assert env["DATABASE_URL"].startswith("postgresql://") and "@db:5432/" in env["DATABASE_URL"]
    assert {"STEAKHOUSE_ADMIN_TOKEN", "STEAKHOUSE_STUDY_FILES"} <= set(env)
    assert (services["app1"]["build"]["context"], (DEPLOY / "../../Dockerfile").resolve()) == (
        "../..", REPO / "Dockerfile")
    example = (DEPLOY / "example.env").read_text(encoding="utf-8")
    assert all(f"{name}=" in example for name in ("DB_PASSWORD", "STEAKHOUSE_ADMIN_TOKEN", "STEAKHOUSE_STUDY_FILES"))


def test_the_docs_refer_to_the_configuration_instead_of_copying_it():
    operations = (REPO / "docs" / "operations.md").read_text(encoding="utf-8")
    assert "server/deploy/nginx.conf" in operations
    assert "upstream steakhouse_play {" not in operations and "proxy_pass" not in operations
    assert "server/deploy/compose.yaml" in (REPO / "docs" / "deploy.md").read_text(encoding="utf-8")


def test_rendering_changes_only_addresses(tmp_path):
    text = CONFIG.read_text(encoding="utf-8")
    out = render(text, backends=["127.0.0.1:1", "127.0.0.1:2", "127.0.0.1:3"], http_port=4, https_port=5,
                 folder=tmp_path)
    assert out.count("server 127.0.0.1:") == 6 and "app1" not in out.replace("`app1", "")
    assert "listen 127.0.0.1:5 ssl;" in out and f"{tmp_path}/study.crt" in out
    with pytest.raises(ValueError, match="listen 443 ssl"):
        render(text.replace("listen 443 ssl;", "listen 8443 ssl;"), backends=["x:1"], http_port=1, https_port=2,
               folder=tmp_path)
