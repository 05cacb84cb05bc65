// The CSE167x scene format (and Glint's extensions) for CodeMirror 6: a stream language that
// marks comments, commands, numbers and file names. Command names come from the module
// (Module.commandNames(), the parser's own table) once it has started; until then any word
// that starts a line is taken for a command.
import { StreamLanguage, HighlightStyle, syntaxHighlighting } from '@codemirror/language';
import { tags } from '@lezer/highlight';

let commands = null;

/// The parser's command names (an array of strings).
export function setCommandNames(names) {
    commands = new Set(names);
}

const courseFormat = StreamLanguage.define({
    name: 'cse167x',
    startState: () => ({ atCommand: true }),
    token(stream, state) {
        if (stream.sol()) state.atCommand = true;
        if (stream.eatSpace()) return null;
        if (stream.peek() === '#') {
            stream.skipToEnd();
            return 'comment';
        }
        if (state.atCommand) {
            state.atCommand = false;
            if (stream.match(/^[A-Za-z_][A-Za-z0-9_]*/)) {
                const word = stream.current();
                return !commands || commands.has(word) ? 'keyword' : 'invalid';
            }
        }
        if (stream.match(/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(?=\s|$)/)) return 'number';
        stream.match(/^\S+/);
        return 'string';
    },
    languageData: { commentTokens: { line: '#' } },
});

const style = HighlightStyle.define([
    { tag: tags.comment, color: '#6a737d', fontStyle: 'italic' },
    { tag: tags.keyword, color: '#005cc5', fontWeight: 'bold' },
    { tag: tags.number, color: '#b35900' },
    { tag: tags.string, color: '#22863a' },
    { tag: tags.invalid, color: '#d73a49', textDecoration: 'underline wavy' },
]);

/// The extension that highlights the format.
export function courseLanguage() {
    return [courseFormat, syntaxHighlighting(style)];
}
