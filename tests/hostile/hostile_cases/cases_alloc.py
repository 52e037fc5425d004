"""Classes 3 and 6: small files that ask for large allocations or quadratic work.

The light-map cases forge the surface table luxel-prep writes into extras.luxel.lightmap
(runtime/include/luxel/scene/lightmap_layout.hpp): the runtime allocates page_size^2
texels per page (IlluminationMaps::page_index) and rasterises TEXCOORD_1 * page_size over the
triangle's texel bounding box (surface_texels.cpp), so both sizes come straight from the file.
"""

from . import case, kit


def alloc(name, description, **kw):
    return case(name, "alloc", description, **kw)


def lightmapped(c, page_size, surfaces, uv1=None, extra_nodes=0, texel_size=0.15):
    """The reference quad with a forged layout; extra_nodes more nodes share its mesh."""
    doc, ids = kit.basic(uv1=uv1 or kit.quad_uv1(page_size, (1, 1, 14, 14)))
    extras = {"luxel": {"lightmap": kit.lightmap(page_size, surfaces, texel_size)}}
    doc.j["nodes"][ids["mesh_node"]]["extras"] = extras
    for i in range(extra_nodes):
        ids["roots"].append(doc.node(mesh=ids["mesh"], extras=extras,
                                     translation=[0, 0, -0.01 * (i + 1)]))
    doc.scene(ids["roots"])
    c.gltf(doc)


alloc("lm-page-65536", "one small surface on a 65536^2 page (16 GiB of texel owners)")(
    lambda c: lightmapped(c, 65536, [kit.surface()]))
alloc("lm-page-16384", "one small surface on a 16384^2 page")(
    lambda c: lightmapped(c, 16384, [kit.surface()]))
alloc("lm-64-pages-4096", "64 surfaces, one per 4096^2 page, in one primitive's table")(
    lambda c: lightmapped(c, 4096, [kit.surface(i, 0, i) for i in range(64)]))
alloc("lm-pages-far-apart", "two surfaces on pages 0 and 2147483647 (page 1024)")(
    lambda c: lightmapped(c, 1024, [kit.surface(0, 0, 0), kit.surface(1, 0, 2147483647)]))
alloc("lm-1000-pages-1024", "1000 surfaces on 1000 pages of 1024^2")(
    lambda c: lightmapped(c, 1024, [kit.surface(i, 0, i) for i in range(1000)]))
alloc("lm-many-charts", "one surface listing 20000 charts")(
    lambda c: lightmapped(c, 64, [kit.surface(charts=[(i % 60, i % 60, 1, 1)
                                                       for i in range(20000)])]))
alloc("lm-texels-huge", "texels 9e18 and area 1e308 in the table")(
    lambda c: lightmapped(c, 16, [kit.surface(area=1e308, texels=9 * 10 ** 18)]))
alloc("lm-texel-size-tiny", "texel_size 1e-30 metres")(
    lambda c: lightmapped(c, 16, [kit.surface()], texel_size=1e-30))
alloc("lm-duplicate-ids", "two surfaces with the same id on one primitive")(
    lambda c: lightmapped(c, 16, [kit.surface(0), kit.surface(0, page=1)]))
alloc("lm-250-instances-4096", "250 nodes share one mesh, each with a 4096^2 light map")(
    lambda c: lightmapped(c, 4096, [kit.surface()], extra_nodes=249))
alloc("lm-250-instances-own-pages", "250 light-mapped nodes of one mesh, each on its own page")(
    lambda c: _own_pages(c, 250, 1024))


def _own_pages(c, count, page_size):
    doc, ids = kit.basic(uv1=kit.quad_uv1(page_size, (1, 1, 14, 14)))
    for i in range(count):
        extras = {"luxel": {"lightmap": kit.lightmap(page_size, [kit.surface(i, 0, i)])}}
        if i == 0:
            doc.j["nodes"][ids["mesh_node"]]["extras"] = extras
        else:
            ids["roots"].append(doc.node(mesh=ids["mesh"], extras=extras))
    doc.scene(ids["roots"])
    c.gltf(doc)


def uv_span(scale, offset=0.0):
    return [(offset + scale * (p[0] + 1) / 2, offset + scale * (p[1] + 1) / 2)
            for p in kit.QUAD_POSITIONS]


alloc("uv1-span-1000-pages", "TEXCOORD_1 spanning 1000 page widths (page 4096)")(
    lambda c: lightmapped(c, 4096, [kit.surface()], uv1=uv_span(1000.0)))
alloc("uv1-span-thousands-16", "TEXCOORD_1 spanning 5000 page widths (page 16)")(
    lambda c: lightmapped(c, 16, [kit.surface()], uv1=uv_span(5000.0)))
alloc("uv1-beyond-int", "TEXCOORD_1 of 1e6 on a 4096 page (texel coordinates beyond int)")(
    lambda c: lightmapped(c, 4096, [kit.surface()], uv1=uv_span(1.0, 1e6)))
alloc("uv1-huge", "TEXCOORD_1 of +-3e38")(
    lambda c: lightmapped(c, 1024, [kit.surface()], uv1=uv_span(3e38, -1.5e38)))
alloc("uv1-negative", "TEXCOORD_1 around -1e9")(
    lambda c: lightmapped(c, 1024, [kit.surface()], uv1=uv_span(1.0, -1e9)))


@alloc("uv1-sliver-65536", "a sliver triangle across a whole 65536 page (huge bounding box)")
def _(c):
    doc, ids = kit.basic(positions=[(-1, -1, 0), (1, 1, 0), (1, 1.001, 0)], indices=[0, 1, 2],
                         uv1=[(0, 0), (1, 1), (1, 0.99999)])
    doc.j["nodes"][ids["mesh_node"]]["extras"] = {"luxel": {"lightmap": kit.lightmap(
        65536, [kit.surface(rect=(0, 0, 65535, 65535), charts=[(0, 0, 65536, 65536)])])}}
    c.gltf(doc)


def instances(c, count, triangles=2):
    if triangles == 2:
        doc, ids = kit.basic()
    else:
        doc, ids = kit.basic(positions=[(-1, -1, 0), (1, -1, 0), (0, 1, 0)],
                             indices=[0, 1, 2] * triangles)
    for i in range(count - 1):
        ids["roots"].append(doc.node(mesh=ids["mesh"], translation=[0, 0, -0.001 * (i + 1)]))
    doc.scene(ids["roots"])
    c.gltf(doc)


alloc("inst-250", "250 nodes referencing one mesh")(lambda c: instances(c, 250))
# The tools prepare an unprepared level at load (prep::load_playable): 2000 instances become
# 4000 light-mapped surfaces on 7M texels, whose lighting and reference frame take longer than the
# corpus's timeout on llvmpipe. The case is about the loader and the instances, so a texel limit
# makes the pipeline refuse, and the level runs unprepared as it did before (with a warning).
alloc("inst-2000", "2000 nodes referencing one mesh",
      args={tool: ["--limit", "lightmap-texels=1M"] for tool in ("sandbox", "ref")})(
    lambda c: instances(c, 2000))
alloc("inst-2000-x-5000-tris", "2000 nodes referencing one 5000-triangle mesh (10M triangles)")(
    lambda c: instances(c, 2000, 5000))


@alloc("nodes-4m-empty", "4 million empty nodes in one 12 MB JSON", big=True)
def _(c):
    c.gltf('{"asset":{"version":"2.0"},"nodes":[' + ",".join(["{}"] * 4_000_000) + "]}")


@alloc("materials-500k-empty", "500000 empty materials (1.5 MB)")
def _(c):
    c.gltf('{"asset":{"version":"2.0"},"materials":[' + ",".join(["{}"] * 500_000) + "]}")


@alloc("nodes-300k-one-mesh", "300000 nodes all referencing one mesh (3.3 MB)")
def _(c):
    doc, ids = kit.basic(light=False, camera=False)
    doc.j["nodes"] = [{"mesh": 0}] * 300_000
    doc.j["scenes"] = [{"nodes": []}]
    c.gltf(doc)


@alloc("primitives-20000", "one mesh with 20000 primitives sharing one accessor")
def _(c):
    doc, ids = kit.basic()
    primitive = doc.j["meshes"][0]["primitives"][0]
    doc.j["meshes"][0]["primitives"] = [primitive] * 20000
    c.gltf(doc)


def textured(c, images, uv=True):
    """The reference quad textured by the first image; every image gets a material and a
    quad of its own so each is decoded and uploaded."""
    doc, ids = kit.basic()
    for i, name in enumerate(images):
        texture = doc.image_texture({"uri": name})
        material = doc.material(pbrMetallicRoughness={"baseColorTexture": {"index": texture},
                                                      "metallicFactor": 0.0})
        if i == 0:
            doc.j["meshes"][0]["primitives"][0]["material"] = material
        else:
            mesh = doc.add("meshes", {"primitives": [dict(doc.j["meshes"][0]["primitives"][0],
                                                          material=material)]})
            ids["roots"].append(doc.node(mesh=mesh, translation=[0, 0, -0.01 * i]))
    doc.scene(ids["roots"])
    c.gltf(doc)


@alloc("png-16384-x6", "six distinct valid 16384^2 PNGs (~35 KB each) on six materials")
def _(c):
    names = []
    for i in range(6):
        names.append(c.write("big%d.png" % i, kit.big_png(16384, 0x80 >> i)))
    textured(c, names)


@alloc("png-16384-x1", "one valid 16384^2 PNG")
def _(c):
    textured(c, [c.write("big.png", kit.big_png(16384, 0x80))])


@alloc("png-16385", "a valid 16385^2 PNG, one texel beyond the edge limit")
def _(c):
    textured(c, [c.write("big.png", kit.big_png(16385, 0x80))])


@alloc("png-16384x1", "a 16384x1 RGBA PNG and a 1x16384 one")
def _(c):
    wide = kit.png(16384, 1, color=6)
    tall = kit.png(1, 16384, color=6)
    textured(c, [c.write("wide.png", wide), c.write("tall.png", tall)])


@alloc("png-16384-x6-same", "the same 16384^2 PNG on six images (decoded once or six times)")
def _(c):
    data = kit.big_png(16384, 0x40)
    textured(c, [c.write("big%d.png" % i, data) for i in range(6)])


def lights(c, count, type_="point", one_light=False):
    """count light nodes (of count lights, or all of light 0) under one parent that lifts
    them off the quad: the children list is the only per-node cost beyond the reference."""
    doc, ids = kit.basic(light=False, lightmapped=True)
    for i in range(1 if one_light else count):
        fields = {"type": type_, "intensity": 0.01}
        if type_ == "spot":
            fields["spot"] = {"outerConeAngle": 0.6}
        doc.light(**fields)
    first = len(doc.j["nodes"])
    for i in range(count):
        doc.light_node(0 if one_light else i)
    ids["roots"].append(doc.node(children=list(range(first, first + count)),
                                 translation=[0, 0, 1.5]))
    doc.scene(ids["roots"])
    c.gltf(doc)


alloc("lights-2000", "2000 point lights")(lambda c: lights(c, 2000))
alloc("lights-50000", "50000 point lights")(lambda c: lights(c, 50000))
alloc("lights-50000-spot", "50000 spot lights")(lambda c: lights(c, 50000, "spot"))
alloc("lights-2000-sun", "2000 directional lights")(lambda c: lights(c, 2000, "directional"))
alloc("lights-50000-nodes-one-light", "50000 nodes referencing one point light")(
    lambda c: lights(c, 50000, one_light=True))


# -- class 6: quadratic loading ---------------------------------------------------------------

def quad_case(name, description):
    return case(name, "quadratic", description)


def coincident(c, triangles, lightmap=True, jitter=0.0, nodes=1):
    positions = []
    indices = []
    uv1 = []
    for t in range(triangles if jitter else 1):
        dz = jitter * t
        positions += [(-1, -1, dz), (1, -1, dz), (0, 1, dz)]
        uv1 += [(1 / 16, 1 / 16), (15 / 16, 1 / 16), (0.5, 15 / 16)]
    for t in range(triangles):
        base = 3 * t if jitter else 0
        indices += [base, base + 1, base + 2]
    doc, ids = kit.basic(positions=positions, indices=indices, uv1=uv1 if lightmap else None)
    if lightmap:
        doc.j["nodes"][ids["mesh_node"]]["extras"] = {"luxel": {"lightmap": kit.lightmap()}}
    for _ in range(nodes - 1):
        ids["roots"].append(doc.node(**doc.j["nodes"][ids["mesh_node"]]))
    doc.scene(ids["roots"])
    c.gltf(doc)


quad_case("coincident-5000", "5000 coincident triangles in one light-mapped surface")(
    lambda c: coincident(c, 5000))
quad_case("coincident-20000", "20000 coincident triangles in one light-mapped surface")(
    lambda c: coincident(c, 20000))
quad_case("coincident-5000-unmapped", "5000 coincident triangles without a light map")(
    lambda c: coincident(c, 5000, lightmap=False))
quad_case("near-coincident-5000", "5000 triangles 1e-6 m apart in one light-mapped surface")(
    lambda c: coincident(c, 5000, jitter=1e-6))
quad_case("coincident-5000-x20-nodes", "20 light-mapped nodes sharing a 5000-triangle mesh")(
    lambda c: coincident(c, 5000, nodes=20))


@quad_case("fan-5000-one-texel", "5000 thin triangles fanned through one light-map texel")
def _(c):
    positions = [(0, 0, 0)]
    uv1 = [(0.5, 0.5)]
    indices = []
    for t in range(5000):
        positions += [(1, t * 1e-4, 0), (1, (t + 1) * 1e-4, 0)]
        uv1 += [(0.5 + 1e-3, 0.5 + t * 1e-7), (0.5 + 1e-3, 0.5 + (t + 1) * 1e-7)]
        indices += [0, 1 + 2 * t, 2 + 2 * t]
    doc, ids = kit.basic(positions=positions, indices=indices, uv1=uv1)
    doc.j["nodes"][ids["mesh_node"]]["extras"] = {"luxel": {"lightmap": kit.lightmap()}}
    c.gltf(doc)
