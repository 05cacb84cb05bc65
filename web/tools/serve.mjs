// Serves a folder over HTTP on localhost, as `make serve` does the web page:
//
//   node web/tools/serve.mjs DIR [--port N] [--no-isolation] [--quiet]
//
// With the cross-origin-isolation headers (Cross-Origin-Opener-Policy: same-origin,
// Cross-Origin-Embedder-Policy: require-corp) the page may use SharedArrayBuffer, so it runs
// the threaded module; --no-isolation leaves them out (the page then runs the single-threaded
// one, as on a host that cannot set headers). Port 0 picks a free port; the first line printed
// is the address.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';

const args = process.argv.slice(2);
const dir = path.resolve(args.find((a) => !a.startsWith('--')) || '.');
const portArg = args.indexOf('--port');
const port = portArg >= 0 ? Number(args[portArg + 1]) : 8167;
const isolation = !args.includes('--no-isolation');
const quiet = args.includes('--quiet');
const types = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
                '.wasm': 'application/wasm', '.css': 'text/css', '.json': 'application/json',
                '.png': 'image/png', '.jpg': 'image/jpeg', '.test': 'text/plain; charset=utf-8',
                '.obj': 'text/plain', '.mtl': 'text/plain' };

if (!fs.existsSync(path.join(dir, 'index.html'))) {
    console.error(`serve: ${dir} has no index.html: run make web first`);
    process.exit(1);
}

const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    let file = path.normalize(path.join(dir, decodeURIComponent(url.pathname)));
    if (!file.startsWith(dir)) {
        res.writeHead(403).end();
        return;
    }
    if (fs.existsSync(file) && fs.statSync(file).isDirectory()) file = path.join(file, 'index.html');
    fs.readFile(file, (err, data) => {
        const headers = { 'Cache-Control': 'no-cache' };
        if (isolation) {
            headers['Cross-Origin-Opener-Policy'] = 'same-origin';
            headers['Cross-Origin-Embedder-Policy'] = 'require-corp';
        }
        if (err) {
            res.writeHead(404, headers).end('not found');
            return;
        }
        headers['Content-Type'] = types[path.extname(file)] || 'application/octet-stream';
        res.writeHead(200, headers).end(data);
        if (!quiet) console.log(`${req.method} ${url.pathname} 200`);
    });
});
server.listen(port, '127.0.0.1', () => {
    const address = `http://localhost:${server.address().port}/`;
    console.log(address);
    if (!quiet)
        console.log(`serving ${dir} ${isolation ? 'with' : 'without'} cross-origin isolation ` +
                    '(Ctrl+C stops)');
});
