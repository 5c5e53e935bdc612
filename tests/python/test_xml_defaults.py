"""The ParaView XML of every TriChart filter: each default_values equals the default of the
filter's property in C++ (its member initializer, taken from the core's options), so that a
filter starts alike in ParaView, Python and C++."""
import pathlib
import xml.etree.ElementTree as ElementTree

import pytest

import trichart

FILTERS = pathlib.Path(__file__).parents[2] / "filters"
NUMERIC = ("IntVectorProperty", "DoubleVectorProperty", "IdTypeVectorProperty")


def filter_proxies():
    """(XML file, proxy element) of every filter and writer; the ParaView representation's XML
    configures a representation, whose defaults ParaView sets on purpose (tests/paraview)."""
    for path in sorted(FILTERS.glob("*/*.xml")):
        if path.parent.name == "ParaView":
            continue
        for group in ElementTree.parse(path).getroot():
            for proxy in group:
                if proxy.get("class"):
                    yield path, proxy


def xml_defaults():
    for path, proxy in filter_proxies():
        for prop in proxy.iter():
            if (prop.tag in NUMERIC and prop.get("default_values") is not None
                    and prop.get("command") and prop.get("information_only") != "1"):
                yield pytest.param(proxy.get("class"), prop.get("command"),
                                   prop.get("default_values"),
                                   id=f"{proxy.get('class')}.{prop.get('name')}")


def test_every_filter_xml_names_a_wrapped_class():
    classes = [proxy.get("class") for _, proxy in filter_proxies()]
    assert len(classes) >= 12, classes
    for name in classes:
        assert hasattr(trichart, name), f"{name} of the XML is not a wrapped TriChart class"


@pytest.mark.parametrize("class_name,command,default", list(xml_defaults()))
def test_xml_default_is_the_cpp_default(class_name, command, default):
    algorithm = getattr(trichart, class_name)()
    value = getattr(algorithm, "Get" + command[len("Set"):])()
    values = list(value) if isinstance(value, (tuple, list)) else [value]
    assert [float(v) for v in values] == [float(v) for v in default.split()], (
        f"{class_name}: {command} defaults to {value} in C++ but {default} in the XML")


def test_lod_representation_error_target_is_the_mappers():
    """The ParaView representation starts on tcLODMapper's error target (1 pixel), as the
    mapper does in C++ and Python and the viewer's panel does."""
    path = FILTERS / "ParaView" / "tcLODRepresentation.xml"
    props = [p for p in ElementTree.parse(path).getroot().iter()
             if p.get("command") == "SetErrorTarget"]
    assert props, "tcLODRepresentation.xml has no ErrorTarget property"
    mapper = trichart.tcLODMapper().GetErrorTarget()
    assert mapper == 1.0
    for prop in props:
        assert float(prop.get("default_values")) == mapper
