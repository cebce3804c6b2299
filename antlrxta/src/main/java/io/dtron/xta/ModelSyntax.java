package io.dtron.xta;

import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.InterfaceSpec;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Query;
import io.dtron.xta.internal.Parsing;
import java.nio.charset.Charset;
import java.nio.charset.StandardCharsets;
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
     * Decodes a model file's bytes: the encoding named in an XML declaration, else UTF-8; a byte-order
     * mark is dropped.
     */
    public static String decode(byte[] bytes) {
        String ascii = new String(bytes, 0, Math.min(bytes.length, 200), StandardCharsets.ISO_8859_1);
        Charset charset = StandardCharsets.UTF_8;
        Matcher m = XML_ENCODING.matcher(stripBom(ascii.replace("\u00ef\u00bb\u00bf", "")));
        if (m.find()) {
            try {
                charset = Charset.forName(m.group(1));
            } catch (IllegalArgumentException unknown) {
                charset = StandardCharsets.UTF_8;
            }
        }
        return stripBom(new String(bytes, charset));
    }

    private static String stripBom(String text) {
        return !text.isEmpty() && text.charAt(0) == '\uFEFF' ? text.substring(1) : text;
    }
}
