"""The command-line reference as reStructuredText, walked from the argparse parser: every
command, its usage, and every option with its default and help. Plain Python (no Sphinx), so
that the tests check it too; ``pollard_docs``' ``cli-reference`` directive renders it.

argparse keeps no public list of a parser's actions: ``_actions``, ``_SubParsersAction`` and
``_choices_actions`` are read here, as every argparse documenter does.
"""
from __future__ import annotations

import argparse


def cli_reference(parser: argparse.ArgumentParser) -> list[str]:
    """The reference of ``parser`` and each of its subcommands, as reStructuredText lines."""
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help or "" for c in sub._choices_actions}
    lines = ["Options of every command", "-" * 24, ""] + _option_lines(parser, True) + [""]
    for name, command in sub.choices.items():
        lines += _command_lines(name, command, helps.get(name, ""))
    return lines


def _default(action: argparse.Action) -> str:
    if action.default in (None, argparse.SUPPRESS) or isinstance(
            action, argparse._StoreTrueAction | argparse._StoreFalseAction
            | argparse._HelpAction | argparse._VersionAction):
        return ""
    shown = action.default if action.default != "" else '""'
    return f" (default: ``{shown}``)"


def _help(action: argparse.Action, prog: str) -> str:
    text = action.help or ""
    if "%" in text:
        params = {k: v for k, v in vars(action).items() if v is not argparse.SUPPRESS}
        params.update(prog=prog, default=action.default)
        if params.get("choices") is not None:
            params["choices"] = ", ".join(map(str, params["choices"]))
        text = text % params
    return " ".join(text.split()).replace("*", r"\*").replace("`", r"\`").replace("|", r"\|")


def _option_lines(parser: argparse.ArgumentParser, top: bool = False) -> list[str]:
    """One bullet per option: its flags and metavar, help, default and choices (a command's
    ``--help`` is said once, with the options of every command)."""
    lines = []
    for action in parser._actions:
        if action.help == argparse.SUPPRESS or isinstance(action, argparse._SubParsersAction) \
                or (isinstance(action, argparse._HelpAction) and not top):
            continue
        if action.option_strings:
            metavar = "" if action.nargs == 0 else " " + (
                action.metavar or action.dest.upper() if not isinstance(action.metavar, tuple)
                else " ".join(action.metavar))
            name = ", ".join(f"``{s}{metavar}``" for s in action.option_strings)
        else:
            name = f"``{action.metavar or action.dest}``"
        if action.choices is not None and not isinstance(action.choices, dict):
            choices = " One of " + ", ".join(f"``{c}``" for c in action.choices) + "."
        else:
            choices = ""
        text = _help(action, parser.prog).rstrip(".")
        if "default" not in text.lower():  # where the help says its default, it says it once
            text = (text + _default(action)).strip()
        lines += [f"* {name}: {text}.{choices}" if text else f"* {name}.{choices}"]
    return lines


def _command_lines(name: str, parser: argparse.ArgumentParser, help_text: str) -> list[str]:
    title = f"``pollard-pin {name}``"
    lines = [f".. _cli-{name}:", "", title, "-" * len(title), ""]
    if help_text:
        lines += [" ".join(help_text.split()), ""]
    usage = parser.format_usage().strip()
    lines += [".. code-block:: text", "", *("    " + u for u in usage.splitlines()), ""]
    desc = parser.description or ""
    if desc.strip() and desc.strip() != help_text.strip():
        lines += [".. code-block:: text", "", *("    " + d for d in desc.strip().splitlines()),
                  ""]
    return lines + _option_lines(parser) + [""]
