//! `route.glb`: the foundation, the block and the CM path as binary glTF 2.0, the route an
//! animation of the block's node (its translation and rotation at each kept pose, linear
//! between them), so that the motion opens in Blender, ParaView or any glTF viewer. The JSON is
//! the glTF project's own types (`gltf-json`); the container is the specification's: a 12-byte
//! header, then a JSON chunk padded with spaces and a BIN chunk padded with zeros, each to four
//! bytes.

use super::{PoseAt, View3d};
use gltf_json as json;
use json::accessor::Type;
use json::buffer::Target;
use json::mesh::{Mode, Semantic};
use json::validation::Checked::Valid;
use json::validation::USize64;

/// Why route.glb could not be made.
#[derive(Debug, thiserror::Error)]
pub enum GlbError {
    /// The JSON could not be written.
    #[error("cannot write its JSON: {0}")]
    Json(#[from] json::Error),
    /// More than a binary glTF holds (4 GiB) or an accessor counts.
    #[error("the scene is too large for binary glTF")]
    TooLarge,
    /// Nothing to animate.
    #[error("the route has no poses")]
    NoPoses,
}

/// The BIN chunk as it is built, and the JSON that describes it.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
    buffer: json::Index<json::Buffer>,
}

impl Builder {
    /// `data` (f32 or u32 values, `width` to an element) appended as a buffer view and an
    /// accessor of `kind`; min and max where `bounds` (glTF requires them of positions and
    /// of an animation's times).
    fn accessor(
        &mut self,
        floats: Option<&[f32]>,
        ints: Option<&[u32]>,
        kind: json::accessor::Type,
        width: usize,
        target: Option<json::buffer::Target>,
        bounds: bool,
    ) -> Result<json::Index<json::Accessor>, GlbError> {
        let offset = self.bin.len();
        let (count, component, min, max) = match (floats, ints) {
            (Some(v), _) => {
                for x in v {
                    self.bin.extend_from_slice(&x.to_le_bytes());
                }
                let (mut lo, mut hi) = (vec![f32::MAX; width], vec![f32::MIN; width]);
                for chunk in v.chunks(width) {
                    for (k, x) in chunk.iter().enumerate() {
                        lo[k] = lo[k].min(*x);
                        hi[k] = hi[k].max(*x);
                    }
                }
                (v.len() / width, json::accessor::ComponentType::F32, lo, hi)
            }
            (None, Some(v)) => {
                for x in v {
                    self.bin.extend_from_slice(&x.to_le_bytes());
                }
                (
                    v.len() / width,
                    json::accessor::ComponentType::U32,
                    vec![],
                    vec![],
                )
            }
            (None, None) => (0, json::accessor::ComponentType::F32, vec![], vec![]),
        };
        let length = self.bin.len() - offset;
        let view = self.root.push(json::buffer::View {
            buffer: self.buffer,
            byte_length: USize64::from(length),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            target: target.map(Valid),
        });
        let value = |v: Vec<f32>| Some(json::Value::from(v));
        Ok(self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64(0)),
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: Default::default(),
            extras: Default::default(),
            type_: Valid(kind),
            min: if bounds { value(min) } else { None },
            max: if bounds { value(max) } else { None },
            name: None,
            normalized: false,
            sparse: None,
        }))
    }

    fn material(
        &mut self,
        name: &str,
        rgba: [f32; 4],
        double_sided: bool,
    ) -> json::Index<json::Material> {
        self.root.push(json::Material {
            name: Some(name.to_string()),
            double_sided,
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: json::material::PbrBaseColorFactor(rgba),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(0.9),
                ..Default::default()
            },
            ..Default::default()
        })
    }

    fn mesh(
        &mut self,
        name: &str,
        attributes: Vec<(json::mesh::Semantic, json::Index<json::Accessor>)>,
        indices: Option<json::Index<json::Accessor>>,
        material: json::Index<json::Material>,
        mode: json::mesh::Mode,
    ) -> json::Index<json::Mesh> {
        let primitive = json::mesh::Primitive {
            attributes: attributes.into_iter().map(|(s, a)| (Valid(s), a)).collect(),
            extensions: Default::default(),
            extras: Default::default(),
            indices,
            material: Some(material),
            mode: Valid(mode),
            targets: None,
        };
        self.root.push(json::Mesh {
            extensions: Default::default(),
            extras: Default::default(),
            name: Some(name.to_string()),
            primitives: vec![primitive],
            weights: None,
        })
    }
}

/// sRGB (0–1) to linear, as glTF's colours are.
fn linear(c: f64) -> f32 {
    let c = c.clamp(0.0, 1.0);
    (if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }) as f32
}

fn f32s<const N: usize>(items: &[[f64; N]]) -> Vec<f32> {
    items.iter().flatten().map(|&v| v as f32).collect()
}

/// The node names a reader finds the parts by.
pub const FOUNDATION: &str = "foundation";
/// The block's node, the one the animation moves.
pub const BLOCK: &str = "block";
/// The CM path's node.
pub const CM_PATH: &str = "cm-path";

/// The binary glTF of `view`.
pub fn glb(view: &View3d) -> Result<Vec<u8>, GlbError> {
    let first = view.poses.first().ok_or(GlbError::NoPoses)?;
    let mut b = Builder::new();
    let mut nodes = Vec::new();
    nodes.extend(b.foundation(view)?);
    let block = b.block(view, first)?;
    nodes.push(block);
    nodes.extend(b.cm_path(view)?);
    b.animation(view, first, block)?;
    b.container(&view.name, nodes)
}

impl Builder {
    /// An empty glTF of one buffer, the BIN chunk.
    fn new() -> Builder {
        let mut root = json::Root {
            asset: json::Asset {
                generator: Some(format!("slideroute {}", env!("CARGO_PKG_VERSION"))),
                version: "2.0".to_string(),
                ..Default::default()
            },
            ..Default::default()
        };
        let buffer = root.push(json::Buffer {
            byte_length: USize64(0),
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            uri: None,
        });
        Builder {
            root,
            bin: Vec::new(),
            buffer,
        }
    }

    /// The foundation's node, in world axes, a colour a corner; none without triangles.
    fn foundation(&mut self, view: &View3d) -> Result<Option<json::Index<json::Node>>, GlbError> {
        if view.ground.triangles.is_empty() {
            return Ok(None);
        }
        let positions = self.accessor(
            Some(&f32s(&view.ground.positions)),
            None,
            Type::Vec3,
            3,
            Some(Target::ArrayBuffer),
            true,
        )?;
        let colors: Vec<f32> = view
            .ground
            .colors
            .iter()
            .flat_map(|c| c.map(linear))
            .collect();
        let colors = self.accessor(
            Some(&colors),
            None,
            Type::Vec3,
            3,
            Some(Target::ArrayBuffer),
            false,
        )?;
        let indices = self.triangles(&view.ground.triangles)?;
        let material = self.material("rock", [1.0, 1.0, 1.0, 1.0], true);
        let mesh = self.mesh(
            FOUNDATION,
            vec![
                (Semantic::Positions, positions),
                (Semantic::Colors(0), colors),
            ],
            Some(indices),
            material,
            Mode::Triangles,
        );
        Ok(Some(self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(FOUNDATION.to_string()),
            ..Default::default()
        })))
    }

    /// The triangles' corners' numbers as an accessor of indices.
    fn triangles(
        &mut self,
        triangles: &[[u32; 3]],
    ) -> Result<json::Index<json::Accessor>, GlbError> {
        let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
        self.accessor(
            None,
            Some(&indices),
            Type::Scalar,
            1,
            Some(Target::ElementArrayBuffer),
            false,
        )
    }

    /// The block's node, in its own axes, at its first pose: the node the animation moves.
    fn block(
        &mut self,
        view: &View3d,
        first: &PoseAt,
    ) -> Result<json::Index<json::Node>, GlbError> {
        let positions = self.accessor(
            Some(&f32s(&view.block.positions)),
            None,
            Type::Vec3,
            3,
            Some(Target::ArrayBuffer),
            true,
        )?;
        let indices = self.triangles(&view.block.triangles)?;
        let concrete = self.material(
            "concrete",
            [linear(0.74), linear(0.72), linear(0.68), 1.0],
            false,
        );
        let mesh = self.mesh(
            BLOCK,
            vec![(Semantic::Positions, positions)],
            Some(indices),
            concrete,
            Mode::Triangles,
        );
        Ok(self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(BLOCK.to_string()),
            translation: Some(first.at.map(|v| v as f32)),
            rotation: Some(json::scene::UnitQuaternion(
                first.rotation.map(|v| v as f32),
            )),
            ..Default::default()
        }))
    }

    /// The CM path's node, a line through the poses' centres of mass; none for one pose.
    fn cm_path(&mut self, view: &View3d) -> Result<Option<json::Index<json::Node>>, GlbError> {
        let cm: Vec<[f64; 3]> = view.poses.iter().map(|p| p.cm).collect();
        if cm.len() < 2 {
            return Ok(None);
        }
        let path = self.accessor(
            Some(&f32s(&cm)),
            None,
            Type::Vec3,
            3,
            Some(Target::ArrayBuffer),
            true,
        )?;
        let red = self.material("cm-path", [linear(0.82), 0.0, linear(0.1), 1.0], false);
        let mesh = self.mesh(
            CM_PATH,
            vec![(Semantic::Positions, path)],
            None,
            red,
            Mode::LineStrip,
        );
        Ok(Some(self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(CM_PATH.to_string()),
            ..Default::default()
        })))
    }

    /// The route: the `block` node's translation and rotation at each pose's time from the
    /// start, linear between them; none for one pose.
    fn animation(
        &mut self,
        view: &View3d,
        first: &PoseAt,
        block: json::Index<json::Node>,
    ) -> Result<(), GlbError> {
        if view.poses.len() < 2 {
            return Ok(());
        }
        let t0 = first.t_s;
        let times: Vec<f32> = view.poses.iter().map(|p| (p.t_s - t0) as f32).collect();
        let times = self.accessor(Some(&times), None, Type::Scalar, 1, None, true)?;
        let at: Vec<[f64; 3]> = view.poses.iter().map(|p| p.at).collect();
        let at = self.accessor(Some(&f32s(&at)), None, Type::Vec3, 3, None, false)?;
        // Each quaternion on the side of the one before, so that no step turns the long way.
        let mut q: Vec<[f64; 4]> = view.poses.iter().map(|p| p.rotation).collect();
        for k in 1..q.len() {
            let dot: f64 = (0..4).map(|i| q[k][i] * q[k - 1][i]).sum();
            if dot < 0.0 {
                q[k] = q[k].map(|v| -v);
            }
        }
        let q = self.accessor(Some(&f32s(&q)), None, Type::Vec4, 4, None, false)?;
        let sampler = |output| json::animation::Sampler {
            extensions: Default::default(),
            extras: Default::default(),
            input: times,
            interpolation: Valid(json::animation::Interpolation::Linear),
            output,
        };
        let channel = |k: u32, path| json::animation::Channel {
            sampler: json::Index::new(k),
            target: json::animation::Target {
                extensions: Default::default(),
                extras: Default::default(),
                node: block,
                path: Valid(path),
            },
            extensions: Default::default(),
            extras: Default::default(),
        };
        self.root.push(json::Animation {
            extensions: Default::default(),
            extras: Default::default(),
            channels: vec![
                channel(0, json::animation::Property::Translation),
                channel(1, json::animation::Property::Rotation),
            ],
            name: Some("route".to_string()),
            samplers: vec![sampler(at), sampler(q)],
        });
        Ok(())
    }

    /// The scene `name` of `nodes`, and the whole as the container: a 12-byte header, the JSON
    /// chunk padded with spaces and the BIN chunk padded with zeros, each to four bytes.
    fn container(
        mut self,
        name: &str,
        nodes: Vec<json::Index<json::Node>>,
    ) -> Result<Vec<u8>, GlbError> {
        let scene = self.root.push(json::Scene {
            extensions: Default::default(),
            extras: Default::default(),
            name: Some(name.to_string()),
            nodes,
        });
        self.root.scene = Some(scene);
        let Builder {
            mut root, mut bin, ..
        } = self;
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        root.buffers[0].byte_length = USize64::from(bin.len());
        let mut text = json::serialize::to_vec(&root)?;
        while text.len() % 4 != 0 {
            text.push(b' ');
        }
        let total = 12 + 8 + text.len() + 8 + bin.len();
        let total = u32::try_from(total).map_err(|_| GlbError::TooLarge)?;
        let size = |n: usize| u32::try_from(n).map_err(|_| GlbError::TooLarge);
        let mut out = Vec::with_capacity(total as usize);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&total.to_le_bytes());
        out.extend_from_slice(&size(text.len())?.to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&size(bin.len())?.to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        Ok(out)
    }
}
