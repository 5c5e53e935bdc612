"""What the pvpython tests share: checks that record a failure and go on, so that one run
reports every broken expectation."""
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)
