"""Thin routers: validate the request, call one service function, shape the answer."""
