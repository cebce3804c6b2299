package io.dtron.xta;

import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.InterfaceSpec;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Query;
import io.dtron.xta.internal.Parsing;
import java.nio.charset.Charset;
import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * The entry point of the front end's syntax stage: turns model text into the AST of {@link io.dtron.xta.ast}
 * with every syntax error reported as a {@link Diagnostic} (file, line, column; for XML labels also template,
 * label kind and column inside the label). Nothing here resolves names or checks types.
 *
 * <p>Expressions, statements, initialiser braces and types nested deeper than 1,000 levels are errors. Parsing
 * runs on a thread with a large stack ({@link LargeStack}), so that nesting up to that limit parses whatever
 * thread asks.
 */
public final class ModelSyntax {
    private static final Pattern XML_ENCODING =
            Pattern.compile("^<\\?xml[^>]*encoding\\s*=\\s*[\"']([A-Za-z0-9._-]+)[\"']");

    private ModelSyntax() {
    }

    /** A model in either format: XML when its first non-blank character is {@code <}, else XTA. */
    public static Parsed<Nta> parseModel(String file, String text) {
        return isXml(text) ? parseXml(file, text) : parseXta(file, text);
    }

    /** Whether {@code text} looks like an XML document. */
    public static boolean isXml(String text) {
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            if (!Character.isWhitespace(c) && c != '\uFEFF') {
                return c == '<';
            }
        }
        return false;
    }

    /** An Uppaal XML model (any DTD version). */
    public static Parsed<Nta> parseXml(String file, String text) {
        return onLargeStack(file, () -> Parsing.xml(file, stripBom(text)));
    }

    /** An {@code .xta} file, or an Uppaal 3 {@code .ta} file. */
    public static Parsed<Nta> parseXta(String file, String text) {
        return onLargeStack(file, () -> Parsing.xta(file, stripBom(text)));
    }

    /** A {@code .q} file of TCTL queries. */
    public static Parsed<List<Query>> parseQueries(String file, String text) {
        return onLargeStack(file, () -> Parsing.queries(file, stripBom(text)));
    }

    /** A TRON interface file ({@code .trn}). */
    public static Parsed<InterfaceSpec> parseInterface(String file, String text) {
        return onLargeStack(file, () -> Parsing.trn(file, stripBom(text)));
    }

    /** One expression, e.g. a guard typed on a command line. */
    public static Parsed<Expr> parseExpression(String file, String text) {
        return onLargeStack(file, () -> Parsing.expression(file, text));
    }

    /** Runs {@code parse} on a large stack; should that still overflow, the text is too deeply nested. */
    private static <T> Parsed<T> onLargeStack(String file, LargeStack.Work<Parsed<T>, RuntimeException> parse) {
        try {
            return LargeStack.call(parse);
        } catch (StackOverflowError e) {
            return new Parsed<>(null, List.of(Diagnostic.fileError(file, "nested too deeply to parse: the parser"
                    + " overflowed its stack of " + LargeStack.MEGABYTES + " MB")));
        }
    }

    /**
     * Decodes a model file's bytes as an XML processor does (XML 1.0, appendix F): a byte-order mark names the
     * encoding (UTF-8, UTF-16 big- or little-endian, UTF-32); without one, the first bytes of {@code <?xml} tell
     * UTF-16 and UTF-32 from the encodings that agree with ASCII, and for those the encoding named in the XML
     * declaration is used ({@code encoding="ISO-8859-1"}, {@code windows-1252}, ...), else UTF-8. The mark is
     * dropped, so that lines and columns count characters of the model's text. XTA files and others without an
     * XML declaration are UTF-8, or whatever their mark says.
     */
    public static String decode(byte[] bytes) {
        int bom = byteOrderMark(bytes);
        return new String(bytes, bom, bytes.length - bom, encodingOf(bytes));
    }

    /** The length of the byte-order mark {@code bytes} start with (UTF-8, UTF-16, UTF-32), 0 when none. */
    public static int byteOrderMark(byte[] bytes) {
        if (startsWith(bytes, 0xEF, 0xBB, 0xBF)) {
            return 3;
        } else if (startsWith(bytes, 0x00, 0x00, 0xFE, 0xFF) || startsWith(bytes, 0xFF, 0xFE, 0x00, 0x00)) {
            return 4;
        } else if (startsWith(bytes, 0xFE, 0xFF) || startsWith(bytes, 0xFF, 0xFE)) {
            return 2;
        }
        return 0;
    }

    /** The encoding of a model file's bytes, found as {@link #decode} says; the byte order is in the name. */
    public static Charset encodingOf(byte[] bytes) {
        if (startsWith(bytes, 0xEF, 0xBB, 0xBF)) {
            return StandardCharsets.UTF_8;
        } else if (startsWith(bytes, 0x00, 0x00, 0xFE, 0xFF) || startsWith(bytes, 0x00, 0x00, 0x00, '<')) {
            return Charset.forName("UTF-32BE");
        } else if (startsWith(bytes, 0xFF, 0xFE, 0x00, 0x00) || startsWith(bytes, '<', 0x00, 0x00, 0x00)) {
            return Charset.forName("UTF-32LE");
        } else if (startsWith(bytes, 0xFE, 0xFF) || startsWith(bytes, 0x00, '<', 0x00, '?')) {
            return StandardCharsets.UTF_16BE;
        } else if (startsWith(bytes, 0xFF, 0xFE) || startsWith(bytes, '<', 0x00, '?', 0x00)) {
            return StandardCharsets.UTF_16LE;
        }
        // an encoding that agrees with ASCII on "<?xml ... encoding='...'?>": the declaration names it
        return declaredEncoding(new String(bytes, 0, Math.min(bytes.length, 200), StandardCharsets.ISO_8859_1));
    }

    private static boolean startsWith(byte[] bytes, int... prefix) {
        if (bytes.length < prefix.length) {
            return false;
        }
        for (int i = 0; i < prefix.length; i++) {
            if ((bytes[i] & 0xFF) != prefix[i]) {
                return false;
            }
        }
        return true;
    }

    /** The encoding an XML declaration at the start of {@code head} names and Java knows, or UTF-8. */
    private static Charset declaredEncoding(String head) {
        Matcher m = XML_ENCODING.matcher(head);
        if (m.find()) {
            try {
                Charset declared = Charset.forName(m.group(1));
                // "UTF-16" declared over bytes that agree with ASCII is a mislabelled file: read what is there
                if (!declared.canEncode() || Arrays.equals(head.substring(0, m.end()).getBytes(declared),
                        head.substring(0, m.end()).getBytes(StandardCharsets.US_ASCII))) {
                    return declared;
                }
            } catch (IllegalArgumentException unknown) {
                // unknown or unsupported: read it as UTF-8, as before
            }
        }
        return StandardCharsets.UTF_8;
    }

    private static String stripBom(String text) {
        return !text.isEmpty() && text.charAt(0) == '\uFEFF' ? text.substring(1) : text;
    }
}
