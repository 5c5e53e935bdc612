#!/usr/bin/env python3
"""Fuzzing the command line of `trichart` (python/trichart/cli.py), in process:

    fuzz_cli.py INPUT...                 replays every command line once (the regression test)
    fuzz_cli.py --seconds S [--seed N] [--timeout T] [--artifacts DIR] SEED...
                                         mutates the seeds for S seconds

Each input is one command line (shlex syntax) in a file. It goes through what `trichart` does
before it starts any work: the parser, then the range checks. Either gives arguments of a
known command, or `trichart: error: ...` (status 2) or the help (status 0); any other
exception, or an input that runs more than T seconds, saves the input as crash-N.txt or
timeout-N.txt in DIR and fails. An in-process loop, not libFuzzer: the parser is Python
(argparse), which libFuzzer cannot instrument; the loop knows the options instead, read from
the parser itself, and mutates with them and with awkward values.
"""
import argparse
import contextlib
import io
import os
import random
import shlex
import signal
import sys
import time
import traceback

from trichart import cli

VALUES = ["0", "-1", "1", "3", "2147483648", "-2147483649", "99999999999999999999999", "1e309",
          "-1e309", "nan", "inf", "-inf", "1e-320", "0x10", "1_000", "", " ", "-", "--", "=",
          "-0", "1.5", "1,5", "٣", "\u00e9.off", "a" * 4096, "mesh.off", "atlas.exr", "out/",
          "/dev/null", "-o", "-q", "--help", "\x00", "\n", "%s%n", "{}"]


class Hang(Exception):
    pass


def options_of(parser):
    """Every option string and subcommand name of `parser` and of its subparsers."""
    words = set()
    for action in parser._actions:  # argparse has no public walk of its actions
        words.update(action.option_strings)
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                words.add(name)
                words.update(options_of(sub))
    return sorted(words)


def commands_of(parser):
    """The subcommand names of `parser`."""
    return {name for action in parser._actions
            if isinstance(action, argparse._SubParsersAction) for name in action.choices}


def run_once(parser, defaults, argv):
    """Parses `argv` as `trichart` does; returns the outcome, raises on a broken contract."""
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            args = parser.parse_args(argv)
            cli._check_args(parser, args, defaults)
    except SystemExit as stop:
        if stop.code == 0:
            return "help"
        message = err.getvalue()
        if stop.code != 2 or "trichart" not in message or "error: " not in message:
            raise AssertionError(f"exit {stop.code!r} without an error message: {message!r}")
        return "refused"
    if args.command not in commands_of(parser):
        raise AssertionError(f"parsed into an unknown command {args.command!r}")
    return "parsed"


def mutate(rng, argv, other, words):
    out = list(argv)
    for _ in range(rng.randint(1, 4)):
        at = rng.randint(0, len(out))
        kind = rng.randrange(9 if out else 3)
        if kind == 0:
            out.insert(at, rng.choice(words))
        elif kind == 1:
            out.insert(at, rng.choice(VALUES))
        elif kind == 2:
            out = out[:at] + other[rng.randint(0, len(other)):]
        elif kind == 3:
            del out[rng.randrange(len(out))]
        elif kind == 4:
            i = rng.randrange(len(out))
            out[i] = rng.choice(VALUES)
        elif kind == 5:  # --option=value, and abbreviations argparse accepts
            i = rng.randrange(len(out))
            if out[i].startswith("--"):
                out[i] = rng.choice([out[i] + "=" + rng.choice(VALUES),
                                     out[i][:rng.randint(2, len(out[i]))]])
        elif kind == 6:
            i, j = rng.randrange(len(out)), rng.randrange(len(out))
            out[i], out[j] = out[j], out[i]
        elif kind == 7:
            out.insert(at, out[rng.randrange(len(out))])
        else:  # a byte of a word changed
            i = rng.randrange(len(out))
            if out[i]:
                k = rng.randrange(len(out[i]))
                out[i] = out[i][:k] + chr(rng.randrange(1, 0x250)) + out[i][k + 1:]
    return out


def read_inputs(paths):
    files = []
    for path in paths:
        if os.path.isdir(path):
            files += sorted(os.path.join(path, f) for f in os.listdir(path)
                            if os.path.isfile(os.path.join(path, f)))
        else:
            files.append(path)
    inputs = []
    for name in files:
        with open(name, encoding="utf-8", errors="surrogateescape") as f:
            inputs.append(shlex.split(f.read()))
    return inputs


def save(artifacts, kind, n, argv):
    path = os.path.join(artifacts, f"{kind}-{n}.txt")
    with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
        f.write(shlex.join(argv) + "\n")
    print(f"tc_fuzz: the input is saved as {path}", file=sys.stderr)


def main():
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--seconds", type=float, default=0.0)
    options.add_argument("--seed", type=int, default=1)
    options.add_argument("--timeout", type=int, default=10)
    options.add_argument("--artifacts", default=".")
    options.add_argument("inputs", nargs="+")
    o = options.parse_args()
    seeds = read_inputs(o.inputs)
    defaults = cli._Defaults()
    parser = cli._parser(defaults)  # parse_args leaves it as it was: one serves every input
    words = options_of(parser)
    rng = random.Random(o.seed)

    def on_alarm(*_):
        raise Hang()
    signal.signal(signal.SIGALRM, on_alarm)

    counts = {"parsed": 0, "refused": 0, "help": 0}
    start = time.monotonic()
    n, crashes, hangs = 0, 0, 0
    while (time.monotonic() - start < o.seconds) if o.seconds > 0 else n < len(seeds):
        argv = mutate(rng, rng.choice(seeds), rng.choice(seeds), words) if o.seconds > 0 \
            else seeds[n]
        signal.alarm(o.timeout)
        try:
            counts[run_once(parser, defaults, argv)] += 1
        except Hang:
            print(f"tc_fuzz: {shlex.join(argv)!r} ran for more than {o.timeout} s (a hang)",
                  file=sys.stderr)
            save(o.artifacts, "timeout", n, argv)
            hangs = 1
        except Exception:  # noqa: BLE001 - any other exception is the crash this looks for
            traceback.print_exc()
            save(o.artifacts, "crash", n, argv)
            crashes = 1
        finally:
            signal.alarm(0)
        n += 1
        if crashes or hangs:
            break  # as libFuzzer does: the first failure ends the run
    seconds = time.monotonic() - start
    print(f"tc_fuzz_cli: {n} executions in {seconds:.1f} s ({n / max(seconds, 1e-9):.0f}/s), "
          f"{counts['parsed']} parsed, {counts['refused']} refused, {counts['help']} help, "
          f"{crashes} crashes, {hangs} hangs")
    return 70 if hangs else 1 if crashes else 0


if __name__ == "__main__":
    sys.exit(main())
