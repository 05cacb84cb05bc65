#!/usr/bin/python3
"""Fine-tunes Open Image Denoise's U-Net weights on Glint's renders (make_data.sh), in PyTorch
(Debian's python3-torch, on the CPU), and writes them as a .tza that Glint reads:

    train.py --data DIR --weights IN.tza --out OUT.tza [--minutes N] [--steps N] [--threads N]
             [--crop 128] [--batch 4] [--lr 3e-5] [--seed 1] [--spp 1,4,16,64] [--log FILE]
    train.py --check IN.tza      the network here against tools/unet_reference.py's
    train.py --rewrite IN.tza OUT.tza   IN through the torch network and the writer (round trip)

The network is built from the archive's tensor names, as tools/unet_reference.py infers it
(OIDN's base, small and large shapes). Its input is OIDN's HDR filter's: colour scaled by the
auto-exposure of the whole noisy image, through the PU transfer function, divided by PU(65504);
albedo clamped to [0, 1]; normal mapped from [-1, 1] to [0, 1]. The loss is taken where the
network's output lives, in that transfer function's space: L1 between the output and the
reference (scaled by the same exposure, through PU), plus L1 between their horizontal and
vertical differences (edges). Adam; random crops (multiples of 16) of random views and sample
counts, flipped and turned by multiples of 90 degrees; fixed seed. Scenes whose name hashes
into the first --val-percent are kept apart for validation; the loss on fixed centre crops of
training and of validation pairs is printed before and after (and for the weights as written,
in float16)."""

import argparse
import glob
import math
import os
import random
import struct
import sys
import time
import zlib

import numpy as np
import torch
import torch.nn.functional as F

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, ".."))
import unet_reference as ref  # noqa: E402  (read_tza, read_pfm, the NumPy network)

# ---------------------------------------------------------------------------------------------
# The network


def levels(names):
    """The encoder's convolutions per level, for the shape the tensor names tell."""
    if "enc_conv1a.weight" in names:  # large
        return [[f"enc_conv{n}a", f"enc_conv{n}b"] for n in range(1, 5)], "dec_conv1c"
    return [["enc_conv0", "enc_conv1"], ["enc_conv2"], ["enc_conv3"], ["enc_conv4"]], "dec_conv0"


class UNet(torch.nn.Module):
    """OIDN's U-Net: 3x3 convolutions with ReLU, 2x2 max pooling, nearest upsampling, skip
    connections by concatenation. Built from a {name: array} of OIDN's tensors."""

    def __init__(self, tensors):
        super().__init__()
        self.encoder, self.last = levels(tensors)
        self.order = list(tensors)  # the archive's order, kept when writing
        self.convs = torch.nn.ModuleDict()
        for key in tensors:
            if key.endswith(".weight"):
                name = key[:-len(".weight")]
                w = torch.from_numpy(np.ascontiguousarray(tensors[key], np.float32))
                b = torch.from_numpy(np.ascontiguousarray(tensors[name + ".bias"], np.float32))
                conv = torch.nn.Conv2d(w.shape[1], w.shape[0], 3, padding=1)
                with torch.no_grad():
                    conv.weight.copy_(w)
                    conv.bias.copy_(b)
                self.convs[name] = conv

    def tensors(self):
        """{name: float32 array} in the archive's order."""
        out = {}
        for key in self.order:
            name, part = key.rsplit(".", 1)
            out[key] = getattr(self.convs[name], part).detach().cpu().numpy().astype(np.float32)
        return out

    def forward(self, x):
        """Input N x C x H x W (sides multiples of 16). The last convolution's output before
        its ReLU: inference clamps it at 0 anyway (OIDN's output transform), and the loss
        then still has a gradient where the network undershoots."""
        def run(names, y):
            for n in names:
                y = F.relu(self.convs[n](y))
            return y

        pools, y = [], x
        for names in self.encoder:
            y = F.max_pool2d(run(names, y), 2)
            pools.append(y)
        y = F.interpolate(run(["enc_conv5a", "enc_conv5b"], y), scale_factor=2, mode="nearest")
        for level in (4, 3, 2):
            y = torch.cat([y, pools[level - 2]], 1)
            y = run([f"dec_conv{level}a", f"dec_conv{level}b"], y)
            y = F.interpolate(y, scale_factor=2, mode="nearest")
        y = run(["dec_conv1a", "dec_conv1b"], torch.cat([y, x], 1))
        return self.convs[self.last](y)


# ---------------------------------------------------------------------------------------------
# OIDN's HDR input and output transforms, in torch (float64 constants from the reference)

P = ref.PU
NORM = float(ref.NORM)


def pu(y):
    """The PU transfer function (linear radiance to perceptual units); differentiable."""
    y = torch.clamp(y, min=0)
    middle = P["b"] * torch.pow(torch.clamp(y, min=1e-30), P["c"]) + P["d"]
    top = P["e"] * torch.log(y + P["f"]) + P["g"]
    return torch.where(y <= P["y0"], P["a"] * y, torch.where(y <= P["y1"], middle, top))


def pu_inverse(x):
    middle = torch.pow(torch.clamp((x - P["d"]) / P["b"], min=0), 1 / P["c"])
    top = torch.exp((x - P["g"]) / P["e"]) - P["f"]
    return torch.where(x <= P["x0"], x / P["a"], torch.where(x <= P["x1"], middle, top))


def network_input(color, albedo, normal, scale):
    """The network's input planes (C x H x W) from H x W x 3 tensors (colour finite, >= 0;
    albedo and normal None where the network takes none)."""
    planes = [pu(color * scale) * NORM]
    if albedo is not None:
        planes.append(torch.clamp(albedo, 0, 1))
    if normal is not None:
        planes.append(torch.clamp(normal, -1, 1) * 0.5 + 0.5)
    return torch.cat(planes, 2).permute(2, 0, 1)


def input_channels(tensors):
    first = "enc_conv1a.weight" if "enc_conv1a.weight" in tensors else "enc_conv0.weight"
    return tensors[first].shape[1]


def denoise(net, color, albedo=None, normal=None):
    """The whole filter on H x W x 3 float64 arrays, as ref.denoise: for --check."""
    color = np.clip(np.nan_to_num(color), 0, None)
    scale = float(ref.exposure(color))
    t = [None if a is None else torch.from_numpy(np.ascontiguousarray(a, np.float32))
         for a in (color, albedo, normal)]
    x = network_input(*t, scale)
    c, h, w = x.shape
    ph, pw = -(-h // 16) * 16, -(-w // 16) * 16
    x = F.pad(x, (0, pw - w, 0, ph - h))[None]
    with torch.no_grad():
        y = torch.clamp(net(x)[0, :, :h, :w], min=0)
    return (pu_inverse(y / NORM) / scale).permute(1, 2, 0).double().numpy()


def check(weights):
    """The torch network and filter against the NumPy reference on small random images."""
    t = ref.read_tza(weights)
    net = UNet(t).eval()
    rng = np.random.default_rng(7)
    channels = input_channels(t)
    x = rng.uniform(0, 1, (channels, 48, 64)).astype(np.float32)
    expected = ref.unet(t, x)
    with torch.no_grad():
        got = torch.clamp(net(torch.from_numpy(x)[None]), min=0)[0].numpy()
    raw = float(np.max(np.abs(got - expected)) / np.max(np.abs(expected)))
    h, w = 37, 53  # not multiples of 16: the padding
    color = np.exp(rng.normal(-1, 2, (h, w, 3)))
    albedo = rng.uniform(0, 1, (h, w, 3))
    normal = rng.normal(0, 1, (h, w, 3))
    normal /= np.linalg.norm(normal, axis=2, keepdims=True)
    aux = [albedo, normal][:channels // 3 - 1]
    a, b = denoise(net, color, *aux), ref.denoise(t, color, *aux)
    whole = float(np.max(np.abs(a - b) / np.maximum(np.maximum(np.abs(a), np.abs(b)), 1e-3)))
    ok = raw < 1e-4 and whole < 1e-3
    print(f"check {os.path.basename(weights)}: raw output differs by {raw:.2e} of its largest "
          f"value, the whole filter by {whole:.2e} relative: {'ok' if ok else 'TOO LARGE'}")
    return ok


# ---------------------------------------------------------------------------------------------
# Weights out: OIDN's tensor archive (version 2, float16, "oihw")


def write_tza(path, tensors):
    """A version 2 tensor archive laid out as OIDN's own files are (byte for byte, for the same
    values): a 16-byte header (magic, version 2.0, the table's offset, 4 zero bytes); each
    tensor's float16 data, 64-byte aligned; the table, 64-byte aligned: the count, then per
    tensor its name, dimensions, layout ("oihw" or "x"), type 'h' and data offset. Written
    aside and renamed into place, so that a reader never sees half a file."""
    body, table = bytearray(), bytearray()
    align = lambda: body.extend(b"\0" * (-(16 + len(body)) % 64))
    for name, array in tensors.items():
        align()
        offset = 16 + len(body)
        body += np.ascontiguousarray(array, "<f2").tobytes()
        layout = "oihw" if array.ndim == 4 else "x" * array.ndim
        table += struct.pack("<H", len(name)) + name.encode() + bytes([array.ndim])
        table += struct.pack(f"<{array.ndim}I", *array.shape) + layout.encode() + b"h"
        table += struct.pack("<Q", offset)
    align()
    with open(path + ".tmp", "wb") as f:
        f.write(struct.pack("<HBBQ", 0x41D7, 2, 0, 16 + len(body)) + b"\0" * 4)
        f.write(bytes(body) + struct.pack("<I", len(tensors)) + bytes(table))
    os.replace(path + ".tmp", path)


# ---------------------------------------------------------------------------------------------
# Data: make_data.sh's PFM files, read as crops are needed


class Data:
    """The (view, spp) pairs of a make_data.sh folder that have colour, albedo, normal and a
    reference; each with its exposure, from the whole noisy image as the filter takes it."""

    def __init__(self, folder, spps, val_percent, channels=9):
        self.folder, self.channels = folder, channels
        self.train, self.val = [], []
        for path in sorted(glob.glob(os.path.join(folder, "*_ref.pfm"))):
            view = os.path.basename(path)[:-len("_ref.pfm")]
            scene = view.rsplit("_v", 1)[0]  # all views of a scene on the same side
            held = zlib.crc32(scene.encode()) % 100 < val_percent
            for spp in spps:
                stem = os.path.join(folder, f"{view}_{spp}")
                if all(os.path.exists(stem + s) for s in (".pfm", ".albedo.pfm", ".normal.pfm")):
                    (self.val if held else self.train).append((view, spp))
        self.scales, self.cache = {}, {}

    def images(self, view, spp):
        """(colour, albedo, normal, reference) H x W x 3 float32, colour and reference finite
        and >= 0, and the exposure."""
        key = (view, spp)
        if key in self.cache:
            return self.cache[key]
        stem = os.path.join(self.folder, f"{view}_{spp}")
        read = lambda p: ref.read_pfm(p).astype(np.float32)
        color = np.clip(np.nan_to_num(read(stem + ".pfm"), posinf=0), 0, None)
        albedo, normal = read(stem + ".albedo.pfm"), read(stem + ".normal.pfm")
        target = read(os.path.join(self.folder, f"{view}_ref.pfm"))
        target = np.clip(np.nan_to_num(target, posinf=0), 0, None)
        if key not in self.scales:
            self.scales[key] = float(ref.exposure(color))
        out = (color, albedo, normal, target, self.scales[key])
        if len(self.cache) < 64:  # a few in memory; the rest read again (a PFM read is cheap)
            self.cache[key] = out
        return out

    def sample(self, key, crop, rng, augment=True):
        """One (input 9 x c x c, target 3 x c x c) pair: a crop of the view at that spp."""
        color, albedo, normal, target, scale = self.images(*key)
        h, w, _ = color.shape
        c = min(crop, h // 16 * 16, w // 16 * 16)
        y0 = rng.randrange(h - c + 1) if augment else (h - c) // 2
        x0 = rng.randrange(w - c + 1) if augment else (w - c) // 2
        window = lambda a: torch.from_numpy(np.ascontiguousarray(a[y0:y0 + c, x0:x0 + c]))
        aux = [window(albedo), window(normal)][:self.channels // 3 - 1]
        x = network_input(window(color), *(aux + [None] * (2 - len(aux))), scale)
        y = pu(window(target) * scale).permute(2, 0, 1) * NORM
        if augment:  # (the normal's values are not turned with the image: OIDN's inputs
            k = rng.randrange(4)  # need not be in any particular frame)
            if rng.random() < 0.5:
                x, y = x.flip(2), y.flip(2)
            x, y = torch.rot90(x, k, (1, 2)), torch.rot90(y, k, (1, 2))
        return x, y

    def batch(self, keys, crop, rng, augment=True):
        pairs = [self.sample(k, crop, rng, augment) for k in keys]
        size = min(p[0].shape[1] for p in pairs)  # (a view smaller than the crop)
        return (torch.stack([p[0][:, :size, :size] for p in pairs]),
                torch.stack([p[1][:, :size, :size] for p in pairs]))


def loss_of(output, target):
    """L1 of the values plus L1 of their horizontal and vertical differences."""
    l1 = torch.mean(torch.abs(output - target))
    dx = lambda a: a[..., :, 1:] - a[..., :, :-1]
    dy = lambda a: a[..., 1:, :] - a[..., :-1, :]
    edges = (torch.mean(torch.abs(dx(output) - dx(target))) +
             torch.mean(torch.abs(dy(output) - dy(target))))
    return l1 + edges


def fixed_loss(net, data, keys, crop, limit=16):
    """The loss on fixed centre crops (no augmentation) of up to `limit` of `keys`, spread
    over them; None if there are none."""
    if not keys:
        return None
    keys = keys[:: max(1, len(keys) // limit)][:limit]
    net.eval()
    total = 0.0
    with torch.no_grad():
        for k in keys:
            x, y = data.batch([k], crop, None, augment=False)
            total += float(loss_of(net(x), y))
    net.train()
    return total / len(keys)


def report(label, net, data, crop):
    """Prints the fixed-crop loss of the training and of the validation pairs."""
    parts = [f"{name} {value:.5f}" for name, value in
             (("training", fixed_loss(net, data, data.train, crop)),
              ("validation", fixed_loss(net, data, data.val, crop))) if value is not None]
    print(f"train: loss on fixed crops {label}: " + ", ".join(parts), flush=True)


# ---------------------------------------------------------------------------------------------


def train(args):
    torch.manual_seed(args.seed)
    rng = random.Random(args.seed)
    torch.set_num_threads(args.threads)
    spps = [s for s in args.spp.split(",") if s]
    tensors = ref.read_tza(args.weights)
    data = Data(args.data, spps, args.val_percent, input_channels(tensors))
    if not data.train:
        sys.exit(f"train: no training images in {args.data} (make_data.sh writes them)")
    print(f"train: {len(data.train)} training pairs, {len(data.val)} validation pairs "
          f"(view x spp), crops {args.crop}, batch {args.batch}, {args.threads} thread(s)")
    net = UNet(tensors)
    net.train()
    optimizer = torch.optim.Adam(net.parameters(), lr=args.lr)
    log = open(args.log, "a") if args.log else None
    report("before", net, data, args.crop)
    start, last_save, step, recent = time.time(), time.time(), 0, []
    window = start
    budget = args.minutes * 60 if args.minutes else math.inf
    while step < (args.steps or math.inf) and time.time() - start < budget:
        # A short warm-up, then the learning rate decays on a cosine over the steps (when the
        # run is sized by --steps) or stays constant.
        lr = args.lr * min(1.0, (step + 1) / args.warmup)
        if args.steps:
            lr *= 0.5 * (1 + math.cos(math.pi * step / args.steps))
        for g in optimizer.param_groups:
            g["lr"] = lr
        x, y = data.batch([rng.choice(data.train) for _ in range(args.batch)], args.crop, rng)
        loss = loss_of(net(x), y)
        optimizer.zero_grad()
        loss.backward()
        optimizer.step()
        step += 1
        recent.append(float(loss))
        if step % args.print_every == 0 or step == 1:
            mean = sum(recent) / len(recent)
            now = time.time()
            line = (f"step {step} loss {mean:.5f} lr {lr:.2e} {(now - window) / len(recent):.2f} "
                    f"s/step elapsed {now - start:.0f} s")
            window = now
            print(line, flush=True)
            if log:
                log.write(line + "\n")
                log.flush()
            recent = []
        if args.save_minutes and time.time() - last_save > args.save_minutes * 60:
            write_tza(args.out, net.tensors())
            last_save = time.time()
    write_tza(args.out, net.tensors())
    elapsed = time.time() - start
    print(f"train: {step} steps in {elapsed:.0f} s ({elapsed / max(step, 1):.2f} s/step); "
          f"wrote {args.out}")
    report("after", net, data, args.crop)
    report("after, as written (float16)", UNet(ref.read_tza(args.out)), data, args.crop)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--check", metavar="TZA", help="compare the network with the NumPy reference")
    p.add_argument("--rewrite", nargs=2, metavar=("IN.tza", "OUT.tza"),
                   help="load IN into the torch network and write it out again (round trip)")
    p.add_argument("--data", help="make_data.sh's output folder")
    p.add_argument("--weights", help="the weights to start from (.tza)")
    p.add_argument("--out", help="the .tza to write")
    p.add_argument("--minutes", type=float, default=0, help="time budget (0: none)")
    p.add_argument("--steps", type=int, default=0, help="number of steps (0: none)")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--crop", type=int, default=128, help="crop side, a multiple of 16")
    p.add_argument("--batch", type=int, default=4)
    p.add_argument("--lr", type=float, default=3e-5, help="Adam's learning rate")
    p.add_argument("--warmup", type=int, default=50, help="steps of linear warm-up")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--spp", default="1,4,16,64", help="the sample counts to train on")
    p.add_argument("--val-percent", type=int, default=10,
                   help="percent of the scenes kept for validation")
    p.add_argument("--print-every", type=int, default=10)
    p.add_argument("--save-minutes", type=float, default=10, help="write the .tza this often")
    p.add_argument("--log", help="append the loss lines to this file")
    args = p.parse_args()
    if args.check:
        torch.set_num_threads(args.threads)
        sys.exit(0 if check(args.check) else 1)
    if args.rewrite:
        write_tza(args.rewrite[1], UNet(ref.read_tza(args.rewrite[0])).tensors())
        return
    if not (args.data and args.weights and args.out):
        p.error("--data, --weights and --out are needed to train (or --check TZA)")
    if args.crop % 16:
        p.error("--crop must be a multiple of 16")
    if not (args.minutes or args.steps):
        p.error("--minutes or --steps is needed")
    train(args)


if __name__ == "__main__":
    main()
